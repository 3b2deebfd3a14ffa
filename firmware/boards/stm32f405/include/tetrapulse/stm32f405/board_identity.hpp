#pragma once
// What this board is: the facts images are checked against and Info reports.
#include <cstdint>

#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "tetrapulse/protocol/version.hpp"
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

// Two decimal digits as BCD (99 at most).
constexpr uint8_t bcd2(uint8_t v) { return static_cast<uint8_t>((v > 99 ? 99 : v) / 10 << 4 | (v > 99 ? 99 : v) % 10); }

// The USB device this board is (SPEC.md §5): application or bootloader, bcdDevice from the
// firmware version (0xMMmm), bus powered at 100 mA, the protocol's DFU attributes.
constexpr protocol::UsbDeviceParams usb_device_params(protocol::UsbMode mode, uint32_t fw_version) {
  protocol::UsbDeviceParams p;
  p.mode = mode;
  p.bcd_device = static_cast<uint16_t>(bcd2(protocol::version_major(fw_version)) << 8 |
                                       bcd2(protocol::version_minor(fw_version)));
  return p;
}
static_assert(usb_device_params(protocol::UsbMode::kApplication, protocol::pack_version(1, 23, 4)).bcd_device ==
              0x0123);

}  // namespace tetrapulse::stm32f405
