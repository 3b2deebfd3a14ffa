#pragma once
// The slot an update writes, and the boot-state steps around it (SPEC.md §7.2, §7.3), for
// updates received while no application runs (the bootloader's DFU and CAN paths).
#include <array>
#include <cstdint>

#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

// The image the board falls back on: the confirmed slot if its image checks, else the
// valid slot with the highest version (slot 0 on a tie), else kNoSlot.
uint8_t known_good_slot(const protocol::Result<BootState>& stored, const std::array<SlotCheck, kSlotCount>& slots);

// The slot an update writes: never the known-good image (even when another slot is
// pending, it is the untested one that gets replaced); slot 0 on a board with none.
uint8_t update_target_slot(const protocol::Result<BootState>& stored, const std::array<SlotCheck, kSlotCount>& slots);

// Erases every sector of `slot` (kFlashError on the first failure).
protocol::Status erase_slot(Flash& flash, const SlotLayout& slot);

// The slot about to be overwritten must not stay pending: the bootloader would try it.
protocol::Status clear_pending_slot(RecordStore& store, uint8_t slot);

// A verified image in `slot` becomes pending (SPEC.md §7.3 step 3): the bootloader gives
// it kMaxTrialBoots starts until it confirms itself. With no stored state, `fallback`
// (the known-good slot, or kNoSlot) becomes the confirmed one.
protocol::Status mark_slot_pending(RecordStore& store, uint8_t slot, uint32_t fw_version, uint8_t fallback);

}  // namespace tetrapulse::fw
