#pragma once
// What this board is: the facts images are checked against and Info reports.
#include <cstdint>

#include "tetrapulse/fw/flash_layout.hpp"
#include "tetrapulse/stm32f405/memory_map.hpp"

namespace tetrapulse::stm32f405 {

// Board revision this firmware reports and checks images against.
constexpr uint8_t kHardwareRevision = 1;
// VTOR alignment on this chip (98 vectors -> 512 bytes).
constexpr uint32_t kVectorAlignment = 512;

// The flash layout of memory_map.hpp in the core's terms.
constexpr fw::FlashLayout flash_layout() {
  fw::FlashLayout l;
  l.record_sectors[0] = fw::FlashRegion{kRecordStoreBase, kRecordSectorSize};
  l.record_sectors[1] = fw::FlashRegion{kRecordStoreBase + kRecordSectorSize, kRecordSectorSize};
  for (uint8_t s = 0; s < kSlotCount; ++s) {
    l.slots[s].region = fw::FlashRegion{kSlotBase[s], kSlotSize};
    l.slots[s].load_address = kSlotBase[s];
  }
  l.vector_alignment = kVectorAlignment;
  return l;
}

}  // namespace tetrapulse::stm32f405
