#pragma once
// Advanced-control (TIM1, TIM8: RM0090 §17) and general-purpose (TIM2..TIM5: §18) timers
// share one register layout; TIM2 and TIM5 have 32-bit CNT, ARR and CCRx.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::tim {

struct Registers {
  Reg CR1;    // 0x00
  Reg CR2;    // 0x04
  Reg SMCR;   // 0x08
  Reg DIER;   // 0x0C
  Reg SR;     // 0x10
  Reg EGR;    // 0x14
  Reg CCMR1;  // 0x18
  Reg CCMR2;  // 0x1C
  Reg CCER;   // 0x20
  Reg CNT;    // 0x24
  Reg PSC;    // 0x28
  Reg ARR;    // 0x2C
  Reg RCR;    // 0x30 (TIM1/TIM8 only)
  Reg CCR[4]; // 0x34..0x40
  Reg BDTR;   // 0x44 (TIM1/TIM8 only)
  Reg DCR;    // 0x48
  Reg DMAR;   // 0x4C
  Reg OR;     // 0x50 (TIM2/TIM5 only)
};
static_assert(offsetof(Registers, CNT) == 0x24);
static_assert(offsetof(Registers, CCR) == 0x34);
static_assert(offsetof(Registers, BDTR) == 0x44);

constexpr uintptr_t kTim2 = 0x40000000;
constexpr uintptr_t kTim1 = 0x40010000;
constexpr uintptr_t kTim8 = 0x40010400;
inline Registers& tim2() { return block<Registers>(kTim2); }
inline Registers& tim8() { return block<Registers>(kTim8); }

// CR1
constexpr uint32_t kCr1Cen = bit(0);
constexpr uint32_t kCr1Udis = bit(1);
constexpr uint32_t kCr1Urs = bit(2);
constexpr uint32_t kCr1Arpe = bit(7);
// CR2: master mode selection (what TRGO carries)
constexpr unsigned kCr2Mms = 4;        // 3 bits
constexpr uint32_t kMmsComparePulse = 3;  // a pulse whenever CC1IF is to be set (capture or match)
// SMCR
constexpr unsigned kSmcrSms = 0;       // 3 bits: slave mode
constexpr unsigned kSmcrTs = 4;        // 3 bits: trigger selection
constexpr uint32_t kSmsReset = 4;      // rising TRGI edge re-initialises the counter and updates registers
constexpr uint32_t kTsItr1 = 1;        // TIM1 and TIM8: ITR1 is TIM2_TRGO (RM0090 trigger connection table)
// DIER / SR
constexpr uint32_t kUif = bit(0);      // update (overflow)
constexpr uint32_t kCc1if = bit(1);
constexpr uint32_t kCc2if = bit(2);
constexpr uint32_t kCc2of = bit(10);   // SR only: a capture was overwritten
// EGR
constexpr uint32_t kEgrUg = bit(0);
// CCMR1/CCMR2: channel n (0..3) uses 8 bits at 8 * (n % 2) of CCMR[n / 2].
constexpr unsigned ccmr_shift(unsigned channel) { return 8 * (channel % 2); }
constexpr uint32_t kCcsOutput = 0;     // CCxS
constexpr uint32_t kCcsInputTi = 1;    // ICx mapped on its own TIx
constexpr uint32_t kOcPreload = bit(3);       // OCxPE: CCRx changes wait for the update event
constexpr unsigned kOcMode = 4;               // OCxM, 3 bits
constexpr uint32_t kOcFrozen = 0;
constexpr uint32_t kOcPwm1 = 6;
constexpr unsigned kIcFilter = 4;             // ICxF, 4 bits
// CCER: channel n uses 4 bits at 4n.
constexpr uint32_t ccer_enable(unsigned channel) { return bit(4 * channel); }
constexpr uint32_t ccer_polarity(unsigned channel) { return bit(4 * channel + 1); }  // CCxP: falling edge for inputs
// BDTR
constexpr uint32_t kBdtrMoe = bit(15);
// RCR (TIM1/TIM8): counter overflows per update event, minus one (8 bits).
constexpr uint32_t kRcrMax = 255;

}  // namespace tetrapulse::stm32f405::tim
