#pragma once
// What a bootloader knows before it decides anything, at reset (boot_slot.hpp) and before it
// takes an update (update_slot.hpp): the record store opened, both slots checked
// (image_check.hpp) and the stored boot state loaded. Every board's bootloader starts here.
#include <array>
#include <cstdint>

#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/boot/image_check.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

struct SlotSurvey {
  std::array<SlotCheck, kSlotCount> checks{};
  std::array<protocol::ImageHeader, kSlotCount> headers{};  // of the slots whose checks pass
  protocol::Result<BootState> stored = protocol::Error::kInvalidState;  // none stored (or unreadable)

  // known_good_slot() and update_target_slot() (update_slot.hpp) of what was found.
  uint8_t known_good() const;
  uint8_t update_target() const;
};

// Opens `store` (over layout.record_sectors of `flash`; unreadable reads as empty, which the
// boot decision treats as a factory-fresh board), checks both slots of `layout` against
// `board` and loads the boot state. `store` stays open for the caller's writes.
SlotSurvey survey_slots(RecordStore& store, const Flash& flash, const FlashLayout& layout, const BoardModel& board);

}  // namespace tetrapulse::fw
