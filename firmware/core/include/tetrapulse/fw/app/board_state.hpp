#pragma once
// Everything the firmware keeps about one board, and the seams it drives: the running
// configuration and the parts that act on it (code player, clock sync, update, record
// store), plus the counters StatusReport reports. Firmware owns one; CommandHandler
// acts on it.
#include <cstdint>

#include "tetrapulse/fw/app/system_control.hpp"
#include "tetrapulse/fw/boot/update_receiver.hpp"
#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/leds/code_player.hpp"
#include "tetrapulse/fw/leds/led_driver.hpp"
#include "tetrapulse/fw/leds/led_log.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/uart_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/fw/sync/sync_controller.hpp"
#include "tetrapulse/fw/sync/sync_input.hpp"
#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::fw {

// What the board is, beyond what SystemControl says.
struct BoardDescription {
  uint32_t fw_version = 0;             // the running image (pack_version)
  uint8_t active_slot = 0;             // the slot running now (Info.active_slot)
  uint32_t capabilities = 0;           // protocol::capability bits
  uint32_t min_bit_period_ns = 10'000; // shortest bit period the LED timer plays (longer is refused: not_supported)
};

// The seams and facts a board hands the firmware. Pointers may be null when the board
// lacks the part (no GPIO sync input, no CAN).
struct FirmwareParts {
  LocalClock* clock = nullptr;
  LedDriver* leds = nullptr;
  Flash* flash = nullptr;
  SystemControl* system = nullptr;
  SyncInput* sync_input = nullptr;
  CanLink* can = nullptr;
  FlashLayout layout;
  BoardDescription board;
};

struct Diagnostics {
  uint16_t rx_malformed = 0;
  protocol::Error last_error = protocol::Error::kNone;
  uint16_t flash_errors = 0;
};

// Saturating counter increment.
inline void bump(uint16_t& counter) {
  if (counter != UINT16_MAX) ++counter;
}

class BoardState {
 public:
  explicit BoardState(const FirmwareParts& parts);

  const FirmwareParts& parts() const { return parts_; }
  LocalClock& clock() const { return *parts_.clock; }
  SystemControl& system() const { return *parts_.system; }
  BoardModel model() const;

  const protocol::Config& config() const { return config_; }
  // not_supported when this board cannot play `config` (SPEC.md §2.5): a bit period
  // below min_bit_period_ns, two_level without the capability, a sync source it lacks.
  protocol::Status supports(const protocol::Config& config) const;
  // Makes `config` the running configuration: code player, clock sync, CAN node, sync input.
  void apply_config(const protocol::Config& config, Tick now);
  uint16_t duty_ceiling() const;

  RecordStore& store() { return store_; }
  const RecordStore& store() const { return store_; }
  LedLog& led_log() { return led_log_; }
  const LedLog& led_log() const { return led_log_; }
  CodePlayer& player() { return player_; }
  const CodePlayer& player() const { return player_; }
  SyncController& sync() { return sync_; }
  const SyncController& sync() const { return sync_; }
  UpdateReceiver& update() { return update_; }
  const UpdateReceiver& update() const { return update_; }
  Diagnostics& diagnostics() { return diagnostics_; }
  const Diagnostics& diagnostics() const { return diagnostics_; }

  uint64_t uptime_ms(Tick now) const;
  // StatusReport.rx_malformed counts the messages that failed to decode and, once set
  // here, the broken frames of the board's UART and USB links (either may be null).
  void set_message_links(const UartLink* uart, const UsbLink* usb) {
    uart_ = uart;
    usb_ = usb;
  }
  protocol::StatusReport status(Tick now) const;

  // Set when a request was answered on some link (boot confirmation needs one).
  bool answered_request = false;

 private:
  FirmwareParts parts_;
  const UartLink* uart_ = nullptr;
  const UsbLink* usb_ = nullptr;
  protocol::Config config_;
  RecordStore store_;
  LedLog led_log_;
  CodePlayer player_;
  SyncController sync_;
  UpdateReceiver update_;
  Diagnostics diagnostics_;
};

}  // namespace tetrapulse::fw
