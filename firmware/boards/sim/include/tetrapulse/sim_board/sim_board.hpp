#pragma once
// A simulated target board: the real firmware core (tetrapulse/fw) on simulated hardware.
// Its crystal runs off true rig time by a drift (ppm) and starts at power-up; its LEDs
// change exactly at scheduled ticks and log each change with its true rig time; its flash
// can lose power at any write step; it has a sync input, a CAN controller, a USB device
// and a UART, all carrying real protocol frames. It has a bootloader too: every reset
// (Reboot, power cycle) picks a firmware slot with the core's boot selection, and with no
// valid slot or asked to stay it waits for an update over CAN or USB DFU (SimBootloader).
//
// Time is true rig time (integer ns). Everything happens in advance_to(t) order: the
// caller moves time forward and feeds events at their rig times, never backwards.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tetrapulse/fw/app/firmware.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/uart_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/response_messages.hpp"
#include "tetrapulse/sim_board/sim_bootloader.hpp"
#include "tetrapulse/sim_board/sim_flash.hpp"
#include "tetrapulse/sim_board/sim_led_driver.hpp"
#include "tetrapulse/sim_board/virtual_clock.hpp"

namespace tetrapulse::sim_board {

struct SimBoardOptions {
  std::array<uint8_t, protocol::kSerialSize> serial{};
  double clock_ppm = 0;              // crystal error (the contract allows +-100 ppm)
  uint8_t node_id = 1;               // stored in the factory configuration
  int64_t power_on_ns = 0;           // rig time at which the board powers up
  uint32_t tick_hz = 84'000'000;     // nominal counter rate (the STM32F405's TIM2 clock)
  uint8_t hw_revision = 1;
  uint32_t fw_version = 0x01000000;  // of the factory image in slot 0
  uint32_t lead_ticks = 168;         // 2 us: how far ahead the LED driver needs a change
  size_t led_queue_depth = 4;
  uint16_t led_full_scale_ma = 1000;
  int64_t poll_interval_ns = 1'000'000;  // the main loop runs at least this often
  bool gpio_sync_input = true;       // capabilities the board has
  bool can = true;
  bool two_level = true;
};

// The simulated board's flash: record store in 4 KB sectors at 0x0 and 0x1000, slot 0 in
// two 8 KB sectors at 0x2000, slot 1 at 0x6000.
fw::FlashLayout sim_flash_layout();
std::vector<fw::FlashRegion> sim_flash_sectors();

class SimBoard {
 public:
  explicit SimBoard(const SimBoardOptions& options);
  ~SimBoard();
  SimBoard(const SimBoard&) = delete;
  SimBoard& operator=(const SimBoard&) = delete;

  const SimBoardOptions& options() const { return options_; }
  int64_t now() const { return now_; }

  // Runs the board up to rig time t (>= now()): LED changes at their ticks, main loop passes.
  void advance_to(int64_t rig_ns);

  // An edge on the sync input at rig time t (the board captures the counter then).
  void sync_edge(int64_t rig_ns);
  // A CAN frame on the bus at rig time t (the controller's acceptance filters apply).
  void can_frame(const protocol::CanFrame& frame, int64_t rig_ns);
  // A bulk OUT transfer, a MESSAGE_OUT control transfer, UART bytes, at rig time t.
  void usb_bulk(protocol::ByteView transfer, int64_t rig_ns);
  void usb_control(protocol::ByteView message, int64_t rig_ns);
  void uart_bytes(protocol::ByteView bytes, int64_t rig_ns);
  // MESSAGE_IN: the oldest answer waiting on the control path (empty: none).
  std::vector<uint8_t> usb_message_in();

  // What the board sent since the last call, in order.
  std::vector<protocol::CanFrame> take_can_frames();
  std::vector<std::vector<uint8_t>> take_usb_bulk();
  std::vector<uint8_t> take_uart_bytes();

  // Every LED change applied since construction, with local tick and true rig time.
  const SimLedDriver& leds() const { return *leds_; }
  // Long runs: the LED log before rig time t is dropped (SimLedDriver::forget_before).
  void forget_led_changes_before(int64_t rig_ns) { leds_->forget_before(static_cast<long double>(rig_ns)); }

  // The CAN controller reports an error (its counter counts it): bus-off from now on (it
  // sends nothing), or back on the bus / still error-active or -passive.
  void can_controller_error(bool bus_off);

  // The crystal changes from now on (holdover tests).
  void set_clock_ppm(double ppm);
  const VirtualClock& clock() const { return clock_; }
  // Local counter now.
  fw::Tick tick() const;

  SimFlash& flash() { return *flash_; }
  // Power off and on at once: RAM state is lost, the board boots from flash.
  void power_cycle();
  // A reset with the power on (the watchdog, a reset button): RAM state is lost, the board
  // boots from flash, and a power cut armed on the flash stays armed.
  void reset();

  // The firmware, or null while the board sits in its bootloader (no valid image, or
  // Reboot{bootloader}).
  fw::Firmware* firmware() { return firmware_ ? &*firmware_ : nullptr; }
  const fw::Firmware* firmware() const { return firmware_ ? &*firmware_ : nullptr; }
  // The bootloader's update paths while no application runs (null otherwise): CAN frames
  // go to it, and a host drives its DFU interface (bootloader()->dfu()).
  SimBootloader* bootloader() { return bootloader_.get(); }
  uint8_t active_slot() const { return active_slot_; }
  uint32_t running_version() const { return running_version_; }
  uint32_t boots() const { return boots_; }
  // Firmware state, shortcuts for tests.
  protocol::StatusReport status() const;

 private:
  class Hardware;

  void boot(bool stay_in_bootloader);
  void after_event();
  void set_now(int64_t rig_ns);

  SimBoardOptions options_;
  int64_t now_ = 0;
  int64_t last_poll_ = 0;
  VirtualClock clock_;
  std::unique_ptr<Hardware> hw_;
  std::unique_ptr<SimFlash> flash_;
  std::unique_ptr<SimLedDriver> leds_;
  std::optional<fw::CanLink> can_link_;
  std::optional<fw::UartLink> uart_link_;
  std::optional<fw::UsbLink> usb_link_;
  std::optional<fw::Firmware> firmware_;
  std::unique_ptr<SimBootloader> bootloader_;
  uint8_t active_slot_ = fw::kNoSlot;
  uint32_t running_version_ = 0;
  uint32_t boots_ = 0;
};

}  // namespace tetrapulse::sim_board
