#pragma once
// Where things live in the STM32F405's flash and RAM (SPEC.md §7). The linker scripts in
// ../../../linker/ use the same numbers; build checks compare them.
//
//   0x08000000  sectors 0-1   32 KB   bootloader
//   0x08008000  sectors 2-3   32 KB   record store (configuration, boot choice)
//   0x08010000  sector 4      64 KB   unused
//   0x08020000  sector 5     128 KB   slot 0: image header, vector table at +0x200
//   0x08040000  sector 6     128 KB   slot 1
#include <cstddef>
#include <cstdint>

namespace tetrapulse::stm32f405 {

constexpr uint32_t kFlashBase = 0x08000000;
constexpr uint32_t kBootloaderBase = 0x08000000;
constexpr uint32_t kBootloaderSize = 32 * 1024;
constexpr uint32_t kRecordStoreBase = 0x08008000;
constexpr uint32_t kRecordSectorSize = 16 * 1024;
constexpr uint8_t kRecordSectorFirst = 2;  // sectors 2 and 3, 16 KB each
constexpr uint32_t kSlotSize = 128 * 1024;
constexpr uint8_t kSlotCount = 2;
constexpr uint32_t kSlotBase[kSlotCount] = {0x08020000, 0x08040000};
constexpr uint8_t kSlotSector[kSlotCount] = {5, 6};
// Images put their vector table here: 82 interrupt vectors + 16 make 392 bytes, which VTOR
// needs aligned to the next power of two, 512 (SPEC.md §7.1).
constexpr uint32_t kVectorOffset = 0x200;
// The application's budget inside a slot (the slot itself is 128 KB).
constexpr uint32_t kApplicationFlashBudget = 64 * 1024;
constexpr uint32_t kApplicationRamBudget = 16 * 1024;

constexpr uint32_t kSramBase = 0x20000000;
constexpr uint32_t kSramSize = 112 * 1024;  // SRAM1; SRAM2 and CCM are unused

// Sector of flash address `address`, or -1 outside the 1 MB array (RM0090 table 5).
constexpr int flash_sector_of(uint32_t address) {
  if (address < kFlashBase) return -1;
  const uint32_t off = address - kFlashBase;
  if (off < 0x10000) return static_cast<int>(off / 0x4000);         // 0..3, 16 KB
  if (off < 0x20000) return 4;                                      // 64 KB
  if (off < 0x100000) return static_cast<int>(4 + off / 0x20000);   // 5..11, 128 KB
  return -1;
}
static_assert(flash_sector_of(0x08020000) == 5 && flash_sector_of(0x08040000) == 6);
static_assert(flash_sector_of(0x0800C000) == 3 && flash_sector_of(0x08010000) == 4);

constexpr int slot_of_address(uint32_t address) {
  for (int s = 0; s < kSlotCount; ++s) {
    if (address >= kSlotBase[s] && address - kSlotBase[s] < kSlotSize) return s;
  }
  return -1;
}

}  // namespace tetrapulse::stm32f405
