#include "tetrapulse/fw/boot/update_slot.hpp"

namespace tetrapulse::fw {

uint8_t known_good_slot(const protocol::Result<BootState>& stored, const std::array<SlotCheck, kSlotCount>& slots) {
  if (stored && stored->confirmed_slot < kSlotCount && slots[stored->confirmed_slot].valid) {
    return stored->confirmed_slot;
  }
  uint8_t best = kNoSlot;
  for (uint8_t s = 0; s < kSlotCount; ++s) {
    if (slots[s].valid && (best == kNoSlot || slots[s].fw_version > slots[best].fw_version)) best = s;
  }
  return best;
}

uint8_t update_target_slot(const protocol::Result<BootState>& stored, const std::array<SlotCheck, kSlotCount>& slots) {
  const uint8_t good = known_good_slot(stored, slots);
  return good == 0 ? 1 : 0;
}

protocol::Status erase_slot(Flash& flash, const SlotLayout& slot) {
  for (uint32_t a = slot.region.address; a < slot.region.end();) {
    const protocol::Result<FlashRegion> sector = flash.sector_at(a);
    if (!sector || !flash.erase_sector(sector->address)) return protocol::Error::kFlashError;
    a = sector->end();
  }
  return {};
}

protocol::Status clear_pending_slot(RecordStore& store, uint8_t slot) {
  const protocol::Result<BootState> state = load_boot_state(store);
  if (!state || state->pending_slot != slot) return {};
  BootState s = *state;
  s.pending_slot = kNoSlot;
  s.attempts = 0;
  s.pending_version = 0;
  return save_boot_state(store, s);
}

protocol::Status mark_slot_pending(RecordStore& store, uint8_t slot, uint32_t fw_version, uint8_t fallback) {
  const protocol::Result<BootState> stored = load_boot_state(store);
  BootState state = stored ? *stored : BootState{};
  if (!stored) state.confirmed_slot = fallback;
  if (state.confirmed_slot == slot) state.confirmed_slot = kNoSlot;  // its image is gone
  state.pending_slot = slot;
  state.attempts = 0;
  state.pending_version = fw_version;
  return save_boot_state(store, state);
}

}  // namespace tetrapulse::fw
