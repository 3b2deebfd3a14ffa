#pragma once
// The whole choice a bootloader makes at reset, shared by every board's bootloader:
// survey the slots (slot_survey.hpp: record store, both slots' checks, the boot state),
// decide (select_boot), store the new boot state, and say what to start.
#include <cstdint>

#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/boot/image_check.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/image_header.hpp"

namespace tetrapulse::fw {

struct BootChoice {
  bool boot = false;           // false: stay in the bootloader
  uint8_t slot = kNoSlot;
  protocol::ImageHeader header;  // of the image to start (its vector table is at
                                 // slot base + header.vector_offset)
  bool state_written = true;   // false when the boot state could not be stored (flash error)
};

// `stay`: Reboot{bootloader} asked to stay.
BootChoice choose_boot_slot(Flash& flash, const FlashLayout& layout, const BoardModel& board, bool stay);

}  // namespace tetrapulse::fw
