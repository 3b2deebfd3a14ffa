// Bootloader (interim boot path): starts the first slot whose image passes every check.
#include "tetrapulse/stm32f405/boot_handoff.hpp"
#include "tetrapulse/stm32f405/clock_tree.hpp"
#include "tetrapulse/stm32f405/memory_map.hpp"
#include "tetrapulse/stm32f405/slot_image.hpp"
#include "tetrapulse/stm32f405/system.hpp"

using namespace tetrapulse::stm32f405;

int main() {
  for (uint8_t slot = 0; slot < kSlotCount; ++slot) {
    const auto h = check_slot_image(kSlotBase[slot], kSlotSize);
    if (!h) continue;
    BootHandoff& handoff = boot_handoff();
    handoff.request = static_cast<uint32_t>(BootRequest::kNone);
    handoff.bootloader_version = TETRAPULSE_FW_VERSION;
    handoff.booted_slot = slot;
    seal_handoff(handoff);
    start_image(kSlotBase[slot] + h->vector_offset);
  }
  for (;;) {
  }
}
