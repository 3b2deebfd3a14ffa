// The bootloader of the STM32F405 reference board: checks both slots, lets the core's
// boot selection (fw/boot_state.hpp) choose, records the choice, and starts the image.
// Clocks stay at their reset values on this path (the application sets them up).
#include <array>
#include <cstdint>

#include "tetrapulse/fw/boot_state.hpp"
#include "tetrapulse/fw/image_check.hpp"
#include "tetrapulse/fw/record_store.hpp"
#include "tetrapulse/stm32f405/board_identity.hpp"
#include "tetrapulse/stm32f405/boot_handoff.hpp"
#include "tetrapulse/stm32f405/internal_flash.hpp"
#include "tetrapulse/stm32f405/system.hpp"

namespace {

namespace fw = tetrapulse::fw;
namespace tp = tetrapulse::protocol;
using namespace tetrapulse::stm32f405;

// Takes (and clears) a Reboot{bootloader} / DFU_DETACH request from the application.
bool take_stay_request(BootHandoff& h) {
  if (!handoff_valid(h)) {
    h = BootHandoff{};
    h.booted_slot = fw::kNoSlot;
    seal_handoff(h);
    return false;
  }
  const bool stay = h.request == static_cast<uint32_t>(BootRequest::kStayInBootloader);
  h.request = static_cast<uint32_t>(BootRequest::kNone);
  seal_handoff(h);
  return stay;
}

}  // namespace

int main() {
  static InternalFlash flash;
  const fw::FlashLayout layout = flash_layout();
  static fw::RecordStore store(flash, layout.record_sectors);
  (void)store.open();  // an unreadable store reads as empty: select_boot handles "no state"

  BootHandoff& handoff = boot_handoff();
  const bool stay = take_stay_request(handoff);
  const fw::BoardModel board{tp::HwModel::kStm32f405Reference, kHardwareRevision};
  std::array<fw::SlotCheck, fw::kSlotCount> checks{};
  std::array<uint32_t, fw::kSlotCount> vector_offsets{};
  for (uint8_t s = 0; s < fw::kSlotCount; ++s) {
    const tp::Result<tp::ImageHeader> h = fw::check_slot_image(flash, layout.slots[s], board, layout.vector_alignment);
    checks[s].valid = h.ok();
    if (h) {
      checks[s].fw_version = h->fw_version;
      vector_offsets[s] = h->vector_offset;
    }
  }

  const fw::BootDecision decision = fw::select_boot(fw::load_boot_state(store), checks, stay);
  if (decision.write_state) (void)fw::save_boot_state(store, decision.state);  // a failed write repeats next boot
  if (decision.boot && decision.slot < fw::kSlotCount) {
    handoff.bootloader_version = TETRAPULSE_FW_VERSION;
    handoff.booted_slot = decision.slot;
    seal_handoff(handoff);
    start_image(layout.slots[decision.slot].load_address + vector_offsets[decision.slot]);
  }
  // No slot to start, or asked to stay: the update paths (USB DFU, CAN) are not bound yet.
  for (;;) {
  }
}
