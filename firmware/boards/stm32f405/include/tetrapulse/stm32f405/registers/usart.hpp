#pragma once
// USART (RM0090 §30.6); USART1 at 0x40011000 on APB2.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::usart {

struct Registers {
  Reg SR;    // 0x00
  Reg DR;    // 0x04
  Reg BRR;   // 0x08
  Reg CR1;   // 0x0C
  Reg CR2;   // 0x10
  Reg CR3;   // 0x14
  Reg GTPR;  // 0x18
};
static_assert(offsetof(Registers, CR1) == 0x0C);

constexpr uintptr_t kUsart1 = 0x40011000;
inline Registers& usart1() { return block<Registers>(kUsart1); }

// SR
constexpr uint32_t kSrFe = bit(1);
constexpr uint32_t kSrNf = bit(2);
constexpr uint32_t kSrOre = bit(3);
constexpr uint32_t kSrRxne = bit(5);
constexpr uint32_t kSrTc = bit(6);
constexpr uint32_t kSrTxe = bit(7);
// CR1
constexpr uint32_t kCr1Re = bit(2);
constexpr uint32_t kCr1Te = bit(3);
constexpr uint32_t kCr1Rxneie = bit(5);
constexpr uint32_t kCr1Txeie = bit(7);
constexpr uint32_t kCr1Ue = bit(13);

}  // namespace tetrapulse::stm32f405::usart
