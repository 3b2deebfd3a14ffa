#include "tetrapulse/stm32f405/internal_flash.hpp"

#include "tetrapulse/stm32f405/memory_map.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/flash.hpp"

namespace tetrapulse::stm32f405 {
namespace {

namespace tp = protocol;
constexpr uint32_t kFlashSize = 1024 * 1024;
// Bounds for BSY: a sector erase takes at most 2 s (x32) and 4 s (x8); a byte program
// at most 100 us. Polls run from flash, which stalls during the operation, so these
// counts bound the wait without mattering on a healthy chip.
constexpr uint32_t kErasePolls = 50'000'000;
constexpr uint32_t kProgramPolls = 100'000;

bool wait_idle(uint32_t polls) {
  flash_if::Registers& f = flash_if::regs();
  for (uint32_t i = 0; i < polls; ++i) {
    if ((f.SR & flash_if::kSrBsy) == 0) return true;
  }
  return false;
}

// Unlocks the control register for the lifetime of the object.
class Unlocked {
 public:
  Unlocked() {
    flash_if::Registers& f = flash_if::regs();
    if ((f.CR & flash_if::kCrLock) != 0) {
      f.KEYR = flash_if::kKey1;
      f.KEYR = flash_if::kKey2;
    }
    f.SR = flash_if::kSrErrors | flash_if::kSrEop;  // write 1 to clear
  }
  ~Unlocked() { flash_if::regs().CR = flash_if::kCrLock; }
  Unlocked(const Unlocked&) = delete;
  Unlocked& operator=(const Unlocked&) = delete;
};

bool in_flash(uint32_t address, size_t size) {
  return address >= kFlashBase && size <= kFlashSize && address - kFlashBase <= kFlashSize - size;
}

const volatile uint8_t* mapped(uint32_t address) { return reinterpret_cast<const volatile uint8_t*>(address); }

}  // namespace

tp::Result<fw::FlashRegion> InternalFlash::do_sector_at(uint32_t address) const {
  const int sector = flash_sector_of(address);
  if (sector < 0) return tp::Error::kBadValue;
  if (sector < 4) return fw::FlashRegion{kFlashBase + 0x4000u * static_cast<uint32_t>(sector), 0x4000};
  if (sector == 4) return fw::FlashRegion{kFlashBase + 0x10000u, 0x10000};
  return fw::FlashRegion{kFlashBase + 0x20000u * static_cast<uint32_t>(sector - 4), 0x20000};
}

tp::Status InternalFlash::do_erase_sector(uint32_t sector_address) {
  const tp::Result<fw::FlashRegion> sector = do_sector_at(sector_address);
  if (!sector || sector->address != sector_address) return tp::Error::kBadValue;
  flash_if::Registers& f = flash_if::regs();
  {
    Unlocked unlocked;
    if (!wait_idle(kProgramPolls)) return tp::Error::kFlashError;
    f.CR = field(flash_if::kPsizeX32, flash_if::kCrPsize) | flash_if::kCrSer |
           field(static_cast<uint32_t>(flash_sector_of(sector_address)), flash_if::kCrSnb);
    f.CR = f.CR | flash_if::kCrStrt;
    const bool idle = wait_idle(kErasePolls);
    f.CR = 0;
    if (!idle || (f.SR & flash_if::kSrErrors) != 0) return tp::Error::kFlashError;
  }
  data_sync_barrier();
  for (uint32_t a = sector->address; a < sector->end(); a += 4) {
    if (*reinterpret_cast<const volatile uint32_t*>(a) != 0xFFFFFFFFu) return tp::Error::kFlashError;
  }
  return {};
}

tp::Status InternalFlash::do_program(uint32_t address, tp::ByteView data) {
  if (!in_flash(address, data.size)) return tp::Error::kBadValue;
  // Programming only clears bits: a byte that is not erased cannot take new data.
  for (size_t i = 0; i < data.size; ++i) {
    if (mapped(address)[i] != 0xFF) return tp::Error::kFlashError;
  }
  flash_if::Registers& f = flash_if::regs();
  Unlocked unlocked;
  if (!wait_idle(kProgramPolls)) return tp::Error::kFlashError;
  f.CR = field(0, flash_if::kCrPsize) | flash_if::kCrPg;  // x8
  bool ok = true;
  for (size_t i = 0; i < data.size && ok; ++i) {
    *reinterpret_cast<volatile uint8_t*>(address + i) = data[i];
    data_sync_barrier();
    ok = wait_idle(kProgramPolls) && (f.SR & flash_if::kSrErrors) == 0;
  }
  f.CR = 0;
  if (!ok) return tp::Error::kFlashError;
  for (size_t i = 0; i < data.size; ++i) {
    if (mapped(address)[i] != data[i]) return tp::Error::kFlashError;
  }
  return {};
}

tp::Status InternalFlash::do_read(uint32_t address, uint8_t* out, size_t size) const {
  if (!in_flash(address, size)) return tp::Error::kBadValue;
  for (size_t i = 0; i < size; ++i) out[i] = mapped(address)[i];
  return {};
}

}  // namespace tetrapulse::stm32f405
