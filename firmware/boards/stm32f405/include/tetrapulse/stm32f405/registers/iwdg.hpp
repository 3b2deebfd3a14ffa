#pragma once
// Independent watchdog (RM0090 §21.4), at 0x40003000, clocked by the ~32 kHz LSI.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::iwdg {

struct Registers {
  Reg KR;   // 0x00
  Reg PR;   // 0x04: prescaler, /4 << PR (0..6)
  Reg RLR;  // 0x08: 12-bit reload
  Reg SR;   // 0x0C: PVU bit 0, RVU bit 1
};

constexpr uintptr_t kBase = 0x40003000;
inline Registers& regs() { return block<Registers>(kBase); }

constexpr uint32_t kKeyStart = 0xCCCC;
constexpr uint32_t kKeyReload = 0xAAAA;
constexpr uint32_t kKeyUnlock = 0x5555;
constexpr uint32_t kSrBusy = bit(0) | bit(1);

}  // namespace tetrapulse::stm32f405::iwdg
