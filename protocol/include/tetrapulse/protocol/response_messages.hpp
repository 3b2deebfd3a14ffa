#pragma once
// Responses, board -> host (SPEC.md §2.6). Field order is wire order.
#include <array>
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/hw_model.hpp"
#include "tetrapulse/protocol/message_type.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// Success of a request without data of its own; `value` per request (SPEC.md §2.6).
struct Ack {
  static constexpr MessageType kType = MessageType::kAck;
  MessageType request_type = MessageType::kGetInfo;  // a defined request type
  uint32_t value = 0;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("request_type", m.request_type);
    io.field("value", m.value);
  }
};

// Info.capabilities bits. Senders set undefined bits to 0; receivers ignore them.
namespace capability {
constexpr uint32_t kUsb = 1u << 0;
constexpr uint32_t kCan = 1u << 1;
constexpr uint32_t kUart = 1u << 2;
constexpr uint32_t kGpioSyncInput = 1u << 3;
constexpr uint32_t kTwoLevel = 1u << 4;       // Modulation::kTwoLevel
constexpr uint32_t kCurrentLimit = 1u << 5;   // Config.current_limit_ma is enforced
constexpr uint32_t kDfu = 1u << 6;            // USB DFU in the bootloader
constexpr uint32_t kCanUpdate = 1u << 7;      // UpdateBegin/Chunk/Verify over CAN
constexpr uint32_t kFrequencyMode = 1u << 8;  // PWM frequency codes
}  // namespace capability

constexpr size_t kSerialSize = 12;

struct Info {
  static constexpr MessageType kType = MessageType::kInfo;
  uint8_t protocol_version = kProtocolVersion;  // the board's protocol version
  HwModel hw_model = HwModel::kStm32f405Reference;
  uint8_t hw_revision = 0;
  uint32_t fw_version = 0;          // pack_version()
  uint32_t bootloader_version = 0;  // pack_version()
  std::array<uint8_t, kSerialSize> serial{};  // 96-bit unique id, as the chip reports it
  uint64_t uptime_ms = 0;
  uint32_t capabilities = 0;  // capability:: bits
  uint8_t node_id = 1;        // 1..254
  uint8_t active_slot = 0;    // firmware slot running now (0-based)
  uint8_t max_code_length = kMaxCodeLength;  // 1..kMaxCodeLength

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("protocol_version", m.protocol_version);
    io.field("hw_model", m.hw_model);
    io.field("hw_revision", m.hw_revision);
    io.field("fw_version", m.fw_version);
    io.field("bootloader_version", m.bootloader_version);
    io.field("serial", m.serial);
    io.field("uptime_ms", m.uptime_ms);
    io.field("capabilities", m.capabilities);
    io.field("node_id", m.node_id);
    io.field("active_slot", m.active_slot);
    io.field("max_code_length", m.max_code_length);
  }
};

struct ConfigReport {
  static constexpr MessageType kType = MessageType::kConfigReport;
  Config config;  // the running configuration

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("config", m.config);
  }
};

enum class SyncState : uint8_t {
  kFreeRunning = 0,  // no sync: local clock only
  kAcquiring = 1,    // sync seen, servo not settled
  kLocked = 2,
  kHoldover = 3,     // was locked, sync lost; running on the last rate estimate
};

enum class UpdateState : uint8_t {
  kIdle = 0,       // no update in progress
  kReceiving = 1,  // after UpdateBegin, chunks arriving
  kVerified = 2,   // UpdateVerify passed; the new image boots on the next Reboot
  kFailed = 3,     // UpdateVerify rejected the image
};

struct StatusReport {
  static constexpr MessageType kType = MessageType::kStatusReport;
  SyncState sync_state = SyncState::kFreeRunning;
  SyncSource sync_source = SyncSource::kNone;  // the source in use
  int32_t offset_ns = 0;      // last measured rig - board clock, saturated to int32
  int32_t rate_ppb = 0;       // estimated local clock rate error, parts per billion
  uint32_t holdover_ms = 0;   // time since the last accepted sync (0 when locked)
  uint32_t sync_accepted = 0;
  uint32_t sync_rejected = 0;  // outliers the servo refused
  uint16_t rx_malformed = 0;   // messages that failed to decode
  uint16_t can_errors = 0;
  uint8_t can_bus_off = 0;     // 0 or 1
  uint16_t flash_errors = 0;
  uint16_t watchdog_resets = 0;
  Error last_error = Error::kNone;  // any Error wire value, including ones this side does not know
  UpdateState update_state = UpdateState::kIdle;
  uint64_t uptime_ms = 0;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("sync_state", m.sync_state);
    io.field("sync_source", m.sync_source);
    io.field("offset_ns", m.offset_ns);
    io.field("rate_ppb", m.rate_ppb);
    io.field("holdover_ms", m.holdover_ms);
    io.field("sync_accepted", m.sync_accepted);
    io.field("sync_rejected", m.sync_rejected);
    io.field("rx_malformed", m.rx_malformed);
    io.field("can_errors", m.can_errors);
    io.field("can_bus_off", m.can_bus_off);
    io.field("flash_errors", m.flash_errors);
    io.field("watchdog_resets", m.watchdog_resets);
    io.field("last_error", m.last_error);
    io.field("update_state", m.update_state);
    io.field("uptime_ms", m.uptime_ms);
  }
};

// One LED edge the code player scheduled: marker `marker` goes to `duty` at `rig_time_ns`.
struct LedLogEntry {
  uint32_t seq = 0;        // running number of the edge
  int64_t rig_time_ns = 0;
  uint8_t marker = 0;      // 0..3
  uint16_t duty = 0;       // 0 = off, 65535 = full

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("seq", m.seq);
    io.field("rig_time_ns", m.rig_time_ns);
    io.field("marker", m.marker);
    io.field("duty", m.duty);
  }
};

constexpr size_t kMaxLedLogEntries = 16;

struct LedLog {
  static constexpr MessageType kType = MessageType::kLedLog;
  uint32_t next = 0;   // ask GetLedLog{first = next} for the entries after these
  uint8_t count = 0;   // 0..kMaxLedLogEntries; the entries fill the rest of the message
  std::array<LedLogEntry, kMaxLedLogEntries> entries{};

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("next", m.next);
    io.tail("count", m.count, "entries", m.entries);
  }
};

// A request failed: which request, why, and a detail for logs (SPEC.md §3).
struct ErrorResponse {
  static constexpr MessageType kType = MessageType::kErrorResponse;
  MessageType request_type = MessageType::kGetInfo;  // type byte of the failed request, any value
  Error error = Error::kNotSupported;                // never kNone; may be a value this side does not know
  uint16_t detail = 0;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("request_type", m.request_type);
    io.field("error", m.error);
    io.field("detail", m.detail);
  }
};

}  // namespace tetrapulse::protocol
