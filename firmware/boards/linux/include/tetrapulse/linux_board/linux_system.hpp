#pragma once
// What the firmware asks of the Linux board itself. A reboot is a request the main loop
// carries out by re-executing the daemon (boot selection runs again, as a bootloader
// would); Reboot{bootloader} and DFU_DETACH restart it in DFU mode.
#include <array>
#include <optional>
#include <string>

#include "tetrapulse/fw/app/system_control.hpp"
#include "tetrapulse/fw/usb/dfu_target.hpp"

namespace tetrapulse::linux_board {

using BoardSerial = std::array<uint8_t, protocol::kSerialSize>;

// The USB serial number string of a board: its unique id in upper-case hex (24 characters).
std::string serial_text(const BoardSerial& serial);
// 24 hex digits; nullopt otherwise.
std::optional<BoardSerial> parse_serial(const std::string& text);
// This computer's id: the first 12 bytes of /etc/machine-id, else a hash of the host name.
BoardSerial machine_serial();

class LinuxSystem final : public fw::SystemControl, public fw::DfuRuntimeTarget {
 public:
  explicit LinuxSystem(const BoardSerial& serial) : serial_(serial) {}
  static constexpr uint8_t kHwRevision = 1;

  // The reset asked for, if any (the main loop restarts the daemon).
  const std::optional<protocol::RebootMode>& requested() const { return requested_; }

 private:
  void do_reboot(protocol::RebootMode mode) override { requested_ = mode; }
  void do_detach() override { requested_ = protocol::RebootMode::kBootloader; }
  BoardSerial do_unique_id() const override { return serial_; }
  protocol::HwModel do_hw_model() const override { return protocol::HwModel::kLinuxBoard; }
  uint8_t do_hw_revision() const override { return kHwRevision; }
  uint32_t do_bootloader_version() const override;
  void do_kick_watchdog() override {}
  uint16_t do_watchdog_resets() const override { return 0; }

  BoardSerial serial_;
  std::optional<protocol::RebootMode> requested_;
};

}  // namespace tetrapulse::linux_board
