#pragma once
// General-purpose I/O ports (RM0090 §8.4); port A at 0x40020000, ports 0x400 apart.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::gpio {

struct Registers {
  Reg MODER;    // 0x00: 2 bits per pin: 0 input, 1 output, 2 alternate function, 3 analog
  Reg OTYPER;   // 0x04
  Reg OSPEEDR;  // 0x08: 2 bits per pin, 3 = very high
  Reg PUPDR;    // 0x0C: 2 bits per pin: 0 none, 1 pull-up, 2 pull-down
  Reg IDR;      // 0x10
  Reg ODR;      // 0x14
  Reg BSRR;     // 0x18
  Reg LCKR;     // 0x1C
  Reg AFR[2];   // 0x20, 0x24: 4 bits per pin
};
static_assert(offsetof(Registers, AFR) == 0x20);

enum class Port : uint8_t { kA = 0, kB = 1, kC = 2 };
constexpr uintptr_t kBaseA = 0x40020000;
constexpr uintptr_t kPortStride = 0x400;
inline Registers& regs(Port p) { return block<Registers>(kBaseA + kPortStride * static_cast<uintptr_t>(p)); }

constexpr uint32_t kModeInput = 0, kModeOutput = 1, kModeAlternate = 2;
constexpr uint32_t kPullNone = 0, kPullUp = 1, kPullDown = 2;
constexpr uint32_t kSpeedVeryHigh = 3;

}  // namespace tetrapulse::stm32f405::gpio
