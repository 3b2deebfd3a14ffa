#include "golden_messages.hpp"

#include "message_testing.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::protocol::testing {
namespace {

Config set_config_example() {
  Config c;
  c.node_id = 17;
  c.target_id = 258;
  c.codes = {code_from_string("1101001110"), code_from_string("1011100100"), Code{},
             code_from_string("1011001110001111000001111110000000111111110000000001111111111000")};
  c.modulation = Modulation::kTwoLevel;
  c.low_level = 19'661;
  c.bit_period_ns = 10'000'000;
  c.epoch_ns = -5'000'000'000;
  c.brightness = 50'000;
  c.current_limit_ma = 350;
  c.sync_source = SyncSource::kGpio;
  c.gpio_edge = GpioEdge::kFalling;
  c.gpio_edge_period_ns = 33'333'333;
  c.gpio_edge_epoch_ns = 1'234'567'890'123;
  c.gpio_edge_numbering = GpioEdgeNumbering::kCountAfterGap;
  return c;
}

UpdateChunk chunk(uint32_t offset, uint16_t length) {
  UpdateChunk m;
  m.offset = offset;
  m.length = length;
  for (size_t i = 0; i < length; ++i) m.data[i] = static_cast<uint8_t>(7 * i + 3);
  return m;
}

Info info_example() {
  Info m;
  m.protocol_version = 1;
  m.hw_model = HwModel::kStm32f405Reference;
  m.hw_revision = 2;
  m.fw_version = pack_version(1, 2, 3);
  m.bootloader_version = pack_version(1, 0, 0);
  for (size_t i = 0; i < m.serial.size(); ++i) m.serial[i] = static_cast<uint8_t>(0x30 + i);
  m.uptime_ms = 123'456'789'012;
  m.capabilities = capability::kUsb | capability::kCan | capability::kUart | capability::kGpioSyncInput |
                   capability::kTwoLevel | capability::kDfu;
  m.node_id = 17;
  m.active_slot = 1;
  m.max_code_length = 64;
  return m;
}

StatusReport status_example() {
  StatusReport m;
  m.sync_state = SyncState::kLocked;
  m.sync_source = SyncSource::kCan;
  m.offset_ns = -1234;
  m.rate_ppb = 15'000;
  m.holdover_ms = 0;
  m.sync_accepted = 1000;
  m.sync_rejected = 3;
  m.rx_malformed = 1;
  m.can_errors = 2;
  m.can_bus_off = 0;
  m.flash_errors = 0;
  m.watchdog_resets = 1;
  m.last_error = Error::kTimeout;
  m.update_state = UpdateState::kIdle;
  m.uptime_ms = 3'600'000;
  return m;
}

LedLog led_log_two() {
  LedLog m;
  m.next = 1002;
  m.count = 2;
  m.entries[0] = LedLogEntry{1000, 20'000'000, 0, 65535};
  m.entries[1] = LedLogEntry{1001, 30'000'000, 3, 19661};
  return m;
}

LedLog led_log_full() {
  LedLog m;
  m.next = 2016;
  m.count = kMaxLedLogEntries;
  for (uint32_t i = 0; i < kMaxLedLogEntries; ++i) {
    m.entries[i] = LedLogEntry{2000 + i, -1'000'000 + int64_t{i} * 10'000'000, static_cast<uint8_t>(i % 4),
                               static_cast<uint16_t>(i * 4099)};
  }
  return m;
}

}  // namespace

std::string golden_key(const std::string& stem, const std::string& record) {
  return record == stem ? stem : stem + "." + record;
}

std::map<std::string, Message> golden_messages() {
  return {
      {"get_info", {1, GetInfo{}}},
      {"get_config", {2, GetConfig{}}},
      {"set_config", {3, SetConfig{set_config_example()}}},
      {"get_status", {4, GetStatus{}}},
      {"identify", {5, Identify{IdentifyPattern::kChase, 5000}}},
      {"persist_config", {6, PersistConfig{}}},
      {"factory_reset", {7, FactoryReset{}}},
      {"reboot", {8, Reboot{RebootMode::kBootloader}}},
      {"update_begin", {9, UpdateBegin{128'000, pack_version(1, 2, 3), 0xE3069283}}},
      {"update_chunk.short", {10, chunk(1024, 5)}},
      {"update_chunk.full", {10, chunk(65536, 256)}},
      {"update_verify", {11, UpdateVerify{}}},
      {"update_abort", {12, UpdateAbort{}}},
      {"get_led_log", {13, GetLedLog{1000}}},
      {"sync", {32, Sync{0xBEEF}}},
      {"follow_up", {33, FollowUp{0xBEEF, 1'700'000'000'123'456'789}}},
      {"ack", {10, Ack{MessageType::kUpdateChunk, 1029}}},
      {"info", {1, info_example()}},
      {"config_report", {2, ConfigReport{default_config()}}},
      {"status_report", {4, status_example()}},
      {"led_log.empty", {13, LedLog{1000, 0, {}}}},
      {"led_log.two", {13, led_log_two()}},
      {"led_log.full", {13, led_log_full()}},
      {"error_response", {10, ErrorResponse{MessageType::kUpdateChunk, Error::kInvalidState, 1024}}},
  };
}

}  // namespace tetrapulse::protocol::testing
