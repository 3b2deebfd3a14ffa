#pragma once
// Flash interface (RM0090 §3.9), at 0x40023C00.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::flash_if {

struct Registers {
  Reg ACR;      // 0x00
  Reg KEYR;     // 0x04
  Reg OPTKEYR;  // 0x08
  Reg SR;       // 0x0C
  Reg CR;       // 0x10
  Reg OPTCR;    // 0x14
};
static_assert(offsetof(Registers, CR) == 0x10);

constexpr uintptr_t kBase = 0x40023C00;
inline Registers& regs() { return block<Registers>(kBase); }

// ACR
constexpr unsigned kAcrLatency = 0;  // 3 bits: wait states
constexpr uint32_t kAcrPrften = bit(8);
constexpr uint32_t kAcrIcen = bit(9);
constexpr uint32_t kAcrDcen = bit(10);
// KEYR unlock sequence
constexpr uint32_t kKey1 = 0x45670123;
constexpr uint32_t kKey2 = 0xCDEF89AB;
// SR
constexpr uint32_t kSrEop = bit(0);
constexpr uint32_t kSrOperr = bit(1);
constexpr uint32_t kSrWrperr = bit(4);
constexpr uint32_t kSrPgaerr = bit(5);
constexpr uint32_t kSrPgperr = bit(6);
constexpr uint32_t kSrPgserr = bit(7);
constexpr uint32_t kSrBsy = bit(16);
constexpr uint32_t kSrErrors = kSrOperr | kSrWrperr | kSrPgaerr | kSrPgperr | kSrPgserr;
// CR
constexpr uint32_t kCrPg = bit(0);
constexpr uint32_t kCrSer = bit(1);
constexpr unsigned kCrSnb = 3;    // 4 bits: sector number
constexpr unsigned kCrPsize = 8;  // 2 bits: 0 x8, 1 x16, 2 x32, 3 x64
constexpr uint32_t kPsizeX32 = 2;
constexpr uint32_t kCrStrt = bit(16);
constexpr uint32_t kCrLock = bit(31);

}  // namespace tetrapulse::stm32f405::flash_if
