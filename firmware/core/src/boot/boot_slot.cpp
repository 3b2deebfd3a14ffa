#include "tetrapulse/fw/boot/boot_slot.hpp"

#include "tetrapulse/fw/storage/record_store.hpp"

namespace tetrapulse::fw {

BootChoice choose_boot_slot(Flash& flash, const FlashLayout& layout, const BoardModel& board, bool stay) {
  RecordStore store(flash, layout.record_sectors);
  store.open();  // unreadable: empty, and select_boot treats it as a factory-fresh board
  std::array<SlotCheck, kSlotCount> checks{};
  std::array<protocol::ImageHeader, kSlotCount> headers{};
  for (uint8_t s = 0; s < kSlotCount; ++s) {
    const protocol::Result<protocol::ImageHeader> h = check_slot_image(flash, layout.slots[s], board, layout.vector_alignment);
    if (h) {
      checks[s] = SlotCheck{true, h->fw_version};
      headers[s] = *h;
    }
  }
  const protocol::Result<BootState> stored = load_boot_state(store);
  BootDecision d = select_boot(stored, checks, stay);
  BootChoice choice;
  if (d.write_state) choice.state_written = save_boot_state(store, d.state).ok();
  if (!choice.state_written && d.boot && d.slot == d.state.pending_slot && stored) {
    // A trial start that could not be counted might repeat forever: run the confirmed
    // image instead.
    BootState without_trial = *stored;
    without_trial.pending_slot = kNoSlot;
    d = select_boot(without_trial, checks, stay);
  }
  choice.boot = d.boot;
  choice.slot = d.slot;
  if (d.boot) choice.header = headers[d.slot];
  return choice;
}

}  // namespace tetrapulse::fw
