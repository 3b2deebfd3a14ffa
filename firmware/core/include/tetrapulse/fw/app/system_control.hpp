#pragma once
// Hardware seam: what the firmware asks of the chip itself: resets, identity, watchdog.
#include <array>
#include <cstdint>

#include "tetrapulse/protocol/hw_model.hpp"
#include "tetrapulse/protocol/request_messages.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::fw {

class SystemControl {
 public:
  // Resets the board; kBootloader asks the bootloader to stay (DFU / wait for an update).
  // On a microcontroller this does not return; a simulated board resets at its next step.
  void reboot(protocol::RebootMode mode) { do_reboot(mode); }
  // 96-bit unique id, in the chip's byte order (Info.serial).
  std::array<uint8_t, protocol::kSerialSize> unique_id() const { return do_unique_id(); }
  protocol::HwModel hw_model() const { return do_hw_model(); }
  uint8_t hw_revision() const { return do_hw_revision(); }
  uint32_t bootloader_version() const { return do_bootloader_version(); }  // pack_version()
  // Restarts the watchdog's countdown; the main loop calls it every pass.
  void kick_watchdog() { do_kick_watchdog(); }
  // Resets caused by the watchdog since power-up (StatusReport.watchdog_resets).
  uint16_t watchdog_resets() const { return do_watchdog_resets(); }

 protected:
  ~SystemControl() = default;

 private:
  virtual void do_reboot(protocol::RebootMode mode) = 0;
  virtual std::array<uint8_t, protocol::kSerialSize> do_unique_id() const = 0;
  virtual protocol::HwModel do_hw_model() const = 0;
  virtual uint8_t do_hw_revision() const = 0;
  virtual uint32_t do_bootloader_version() const = 0;
  virtual void do_kick_watchdog() = 0;
  virtual uint16_t do_watchdog_resets() const = 0;
};

}  // namespace tetrapulse::fw
