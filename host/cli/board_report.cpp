#include "board_report.hpp"

#include <fmt/format.h>

#include "json_text.hpp"
#include "tetrapulse/host/config_text.hpp"
#include "tetrapulse/host/firmware_image.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::cli {

using protocol::StatusReport;

std::string version_text(uint32_t v) {
  return fmt::format("{}.{}.{}", protocol::version_major(v), protocol::version_minor(v), protocol::version_patch(v));
}

std::string serial_text(const protocol::Info& info) {
  std::string s;
  for (uint8_t b : info.serial) s += fmt::format("{:02X}", b);
  return s;
}

std::string capabilities_text(uint32_t c) {
  static const char* const kNames[] = {"usb",        "can",           "uart",         "gpio-sync", "two-level",
                                       "current-limit", "usb-dfu", "can-update", "frequency-codes"};
  std::string out;
  for (size_t i = 0; i < sizeof(kNames) / sizeof(kNames[0]); ++i) {
    if ((c & (1u << i)) != 0) out += (out.empty() ? "" : " ") + std::string(kNames[i]);
  }
  return out.empty() ? "none" : out;
}

namespace {

const char* sync_state_name(protocol::SyncState s) {
  switch (s) {
    case protocol::SyncState::kFreeRunning: return "free-running";
    case protocol::SyncState::kAcquiring: return "acquiring";
    case protocol::SyncState::kLocked: return "locked";
    case protocol::SyncState::kHoldover: return "holdover";
  }
  return "unknown";
}

const char* update_state_name(protocol::UpdateState s) {
  switch (s) {
    case protocol::UpdateState::kIdle: return "idle";
    case protocol::UpdateState::kReceiving: return "receiving";
    case protocol::UpdateState::kVerified: return "verified";
    case protocol::UpdateState::kFailed: return "failed";
  }
  return "unknown";
}

}  // namespace

std::string format_info(const std::string& address, const protocol::Info& i) {
  return fmt::format(
      "{}\n  hardware: {} rev {}\n  firmware: {} (slot {}), bootloader {}\n  serial: {}\n  node id: {}\n"
      "  protocol: {}\n  capabilities: {}\n  longest code: {} bits\n  uptime: {:.1f} s\n",
      address, host::hw_model_name(i.hw_model), i.hw_revision, version_text(i.fw_version), i.active_slot,
      version_text(i.bootloader_version), serial_text(i), i.node_id, i.protocol_version,
      capabilities_text(i.capabilities), i.max_code_length, static_cast<double>(i.uptime_ms) / 1000.0);
}

std::string info_json(const std::string& address, const protocol::Info& i) {
  return JsonObject()
      .str("address", address)
      .str("hw_model", host::hw_model_name(i.hw_model))
      .num("hw_revision", i.hw_revision)
      .str("fw_version", version_text(i.fw_version))
      .str("bootloader_version", version_text(i.bootloader_version))
      .str("serial", serial_text(i))
      .num("node_id", i.node_id)
      .num("active_slot", i.active_slot)
      .num("protocol_version", i.protocol_version)
      .num("capabilities", i.capabilities)
      .num("max_code_length", i.max_code_length)
      .num("uptime_ms", i.uptime_ms)
      .text();
}

std::string format_status(const StatusReport& s) {
  std::string line = fmt::format("sync {} ({}), offset {} ns, rate {} ppb, accepted {}, rejected {}",
                                 sync_state_name(s.sync_state), host::sync_source_name(s.sync_source), s.offset_ns,
                                 s.rate_ppb, s.sync_accepted, s.sync_rejected);
  if (s.sync_state == protocol::SyncState::kHoldover) line += fmt::format(", holdover {} ms", s.holdover_ms);
  line += fmt::format("; update {}; uptime {:.1f} s", update_state_name(s.update_state),
                      static_cast<double>(s.uptime_ms) / 1000.0);
  if (s.can_bus_off != 0) line += "; CAN BUS-OFF";
  if (s.can_errors != 0) line += fmt::format("; CAN errors {}", s.can_errors);
  if (s.rx_malformed != 0) line += fmt::format("; malformed {}", s.rx_malformed);
  if (s.flash_errors != 0) line += fmt::format("; flash errors {}", s.flash_errors);
  if (s.watchdog_resets != 0) line += fmt::format("; watchdog resets {}", s.watchdog_resets);
  if (s.last_error != protocol::Error::kNone) line += fmt::format("; last error {}", protocol::error_name(s.last_error));
  return line;
}

std::string status_json(const std::string& address, const StatusReport& s) {
  return JsonObject()
      .str("address", address)
      .str("sync_state", sync_state_name(s.sync_state))
      .str("sync_source", host::sync_source_name(s.sync_source))
      .num("offset_ns", s.offset_ns)
      .num("rate_ppb", s.rate_ppb)
      .num("holdover_ms", s.holdover_ms)
      .num("sync_accepted", s.sync_accepted)
      .num("sync_rejected", s.sync_rejected)
      .num("rx_malformed", s.rx_malformed)
      .num("can_errors", s.can_errors)
      .flag("can_bus_off", s.can_bus_off != 0)
      .num("flash_errors", s.flash_errors)
      .num("watchdog_resets", s.watchdog_resets)
      .str("last_error", protocol::error_name(s.last_error))
      .str("update_state", update_state_name(s.update_state))
      .num("uptime_ms", s.uptime_ms)
      .text();
}

std::string config_json(const std::string& address, const protocol::Config& c) {
  std::string codes = "[";
  for (size_t i = 0; i < c.codes.size(); ++i) codes += (i ? ", " : "") + json_string(host::code_text(c.codes[i]));
  codes += "]";
  return JsonObject()
      .str("address", address)
      .num("node_id", c.node_id)
      .num("target_id", c.target_id)
      .raw("codes", codes)
      .str("modulation", host::modulation_name(c.modulation))
      .num("low_level", c.low_level)
      .num("bit_period_ns", c.bit_period_ns)
      .num("epoch_ns", c.epoch_ns)
      .num("brightness", c.brightness)
      .num("current_limit_ma", c.current_limit_ma)
      .str("sync_source", host::sync_source_name(c.sync_source))
      .str("gpio_edge", host::gpio_edge_name(c.gpio_edge))
      .num("gpio_edge_period_ns", c.gpio_edge_period_ns)
      .num("gpio_edge_epoch_ns", c.gpio_edge_epoch_ns)
      .str("gpio_edge_numbering", host::gpio_edge_numbering_name(c.gpio_edge_numbering))
      .text();
}

}  // namespace tetrapulse::cli
