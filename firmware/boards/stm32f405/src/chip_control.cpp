#include "tetrapulse/stm32f405/chip_control.hpp"

#include "tetrapulse/stm32f405/boot_handoff.hpp"
#include "tetrapulse/stm32f405/board_identity.hpp"
#include "tetrapulse/stm32f405/watchdog.hpp"

namespace tetrapulse::stm32f405 {

void ChipControl::start(const ResetCause& cause, bool has_system_memory) {
  if (has_system_memory) unique_id_ = unique_id();
  BootHandoff& h = boot_handoff();
  if (handoff_valid(h)) {
    bootloader_version_ = h.bootloader_version;
    booted_slot_ = static_cast<uint8_t>(h.booted_slot);
    uint32_t resets = cause.power_on ? 0 : h.watchdog_resets;
    if (cause.watchdog && resets < UINT16_MAX) ++resets;
    h.watchdog_resets = resets;
    seal_handoff(h);
    watchdog_resets_ = static_cast<uint16_t>(resets);
  } else {
    watchdog_resets_ = cause.watchdog ? 1 : 0;
  }
}

uint8_t ChipControl::do_hw_revision() const { return kHardwareRevision; }

void ChipControl::do_reboot(protocol::RebootMode mode) {
  usart1().drain();  // the Ack leaves before the reset (SPEC §2.3 Reboot)
  BootHandoff& h = boot_handoff();
  if (!handoff_valid(h)) {
    h = BootHandoff{};
    h.booted_slot = 0xFF;
  }
  h.request = static_cast<uint32_t>(mode == protocol::RebootMode::kBootloader ? BootRequest::kStayInBootloader
                                                                               : BootRequest::kNone);
  h.watchdog_resets = watchdog_resets_;
  seal_handoff(h);
  system_reset();
}

void ChipControl::do_kick_watchdog() { feed_watchdog(); }

}  // namespace tetrapulse::stm32f405
