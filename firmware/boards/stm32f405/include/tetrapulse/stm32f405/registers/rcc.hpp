#pragma once
// Reset and clock control (RM0090 §7.3), at 0x40023800.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::rcc {

struct Registers {
  Reg CR;          // 0x00
  Reg PLLCFGR;     // 0x04
  Reg CFGR;        // 0x08
  Reg CIR;         // 0x0C
  Reg AHB1RSTR;    // 0x10
  Reg AHB2RSTR;    // 0x14
  Reg AHB3RSTR;    // 0x18
  Reg reserved0;   // 0x1C
  Reg APB1RSTR;    // 0x20
  Reg APB2RSTR;    // 0x24
  Reg reserved1[2];
  Reg AHB1ENR;     // 0x30
  Reg AHB2ENR;     // 0x34
  Reg AHB3ENR;     // 0x38
  Reg reserved2;
  Reg APB1ENR;     // 0x40
  Reg APB2ENR;     // 0x44
  Reg reserved3[2];
  Reg AHB1LPENR;   // 0x50
  Reg AHB2LPENR;   // 0x54
  Reg AHB3LPENR;   // 0x58
  Reg reserved4;
  Reg APB1LPENR;   // 0x60
  Reg APB2LPENR;   // 0x64
  Reg reserved5[2];
  Reg BDCR;        // 0x70
  Reg CSR;         // 0x74
};
static_assert(offsetof(Registers, AHB1ENR) == 0x30);
static_assert(offsetof(Registers, APB1ENR) == 0x40);
static_assert(offsetof(Registers, CSR) == 0x74);

constexpr uintptr_t kBase = 0x40023800;
inline Registers& regs() { return block<Registers>(kBase); }

// CR
constexpr uint32_t kCrHsiOn = bit(0);
constexpr uint32_t kCrHsiRdy = bit(1);
constexpr uint32_t kCrHseOn = bit(16);
constexpr uint32_t kCrHseRdy = bit(17);
constexpr uint32_t kCrHseByp = bit(18);
constexpr uint32_t kCrCssOn = bit(19);
constexpr uint32_t kCrPllOn = bit(24);
constexpr uint32_t kCrPllRdy = bit(25);

// PLLCFGR: f_vco = f_in * N / M, f_sys = f_vco / P, f_usb = f_vco / Q.
constexpr unsigned kPllM = 0;       // 6 bits, 2..63
constexpr unsigned kPllN = 6;       // 9 bits, 50..432
constexpr unsigned kPllP = 16;      // 2 bits: 0 -> /2, 1 -> /4, 2 -> /6, 3 -> /8
constexpr uint32_t kPllSrcHse = bit(22);
constexpr unsigned kPllQ = 24;      // 4 bits, 2..15

// CFGR
constexpr unsigned kCfgrSw = 0;     // 2 bits: 0 HSI, 1 HSE, 2 PLL
constexpr unsigned kCfgrSws = 2;    // 2 bits, read-only status of SW
constexpr unsigned kCfgrHpre = 4;   // 4 bits: 0xxx = /1
constexpr unsigned kCfgrPpre1 = 10; // 3 bits: 100 /2, 101 /4, 110 /8
constexpr unsigned kCfgrPpre2 = 13; // 3 bits
constexpr uint32_t kSwHsi = 0, kSwHse = 1, kSwPll = 2;
constexpr uint32_t kPpreDiv2 = 4, kPpreDiv4 = 5;

// AHB1ENR
constexpr uint32_t kAhb1GpioA = bit(0);
constexpr uint32_t kAhb1GpioB = bit(1);
constexpr uint32_t kAhb1GpioC = bit(2);
constexpr uint32_t kAhb1Crc = bit(12);
// AHB2ENR
constexpr uint32_t kAhb2OtgFs = bit(7);
// APB1ENR
constexpr uint32_t kApb1Tim2 = bit(0);
constexpr uint32_t kApb1Can1 = bit(25);
constexpr uint32_t kApb1Pwr = bit(28);
// APB2ENR
constexpr uint32_t kApb2Tim1 = bit(0);
constexpr uint32_t kApb2Tim8 = bit(1);
constexpr uint32_t kApb2Usart1 = bit(4);
constexpr uint32_t kApb2Syscfg = bit(14);

// CSR: reset flags (cleared together by RMVF)
constexpr uint32_t kCsrLsiOn = bit(0);
constexpr uint32_t kCsrLsiRdy = bit(1);
constexpr uint32_t kCsrRmvf = bit(24);
constexpr uint32_t kCsrPinRst = bit(26);
constexpr uint32_t kCsrPorRst = bit(27);
constexpr uint32_t kCsrSftRst = bit(28);
constexpr uint32_t kCsrIwdgRst = bit(29);

}  // namespace tetrapulse::stm32f405::rcc
