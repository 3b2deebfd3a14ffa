#pragma once
// Where a board keeps what: two record-store sectors (configuration and boot state) and
// two firmware slots (SPEC.md §7.2). The layout is the board's; the core only reads it.
//
// stm32f405: bootloader in sectors 0-1; record store in the 16 KB sectors 2 and 3
// (0x08008000, 0x0800C000); slot 0 = sector 5 (0x08020000, 128 KB), slot 1 = sector 6
// (0x08040000, 128 KB).
#include <array>
#include <cstdint>

#include "tetrapulse/fw/storage/flash.hpp"

namespace tetrapulse::fw {

constexpr uint8_t kSlotCount = 2;
constexpr uint8_t kNoSlot = 0xFF;

struct SlotLayout {
  FlashRegion region;         // whole erase sectors
  uint32_t load_address = 0;  // the load_address an image for this slot carries (SPEC.md §7.1)
};

struct FlashLayout {
  std::array<FlashRegion, 2> record_sectors{};  // each exactly one erase sector
  std::array<SlotLayout, kSlotCount> slots{};
  uint32_t vector_alignment = 128;  // the board's own rule for vector_offset (stm32f405: 512)
};

}  // namespace tetrapulse::fw
