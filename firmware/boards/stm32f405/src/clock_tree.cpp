#include "tetrapulse/stm32f405/clock_tree.hpp"

#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/flash.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"

namespace tetrapulse::stm32f405 {
namespace {

// HSE start-up takes up to 2 ms (datasheet); at 16 MHz HSI a poll iteration is several
// cycles, so 200 000 polls is well over 10 ms. The same bound serves PLL lock (~100 us).
constexpr uint32_t kReadyPolls = 200'000;

bool wait_set(Reg& reg, uint32_t bits, uint32_t value) {
  for (uint32_t i = 0; i < kReadyPolls; ++i) {
    if ((reg & bits) == value) return true;
  }
  return false;
}

constexpr uint32_t kPllM = kHseHz / 1'000'000;  // 1 MHz PLL input
constexpr uint32_t kPllN = 336;                 // 336 MHz VCO
constexpr uint32_t kPllP = 0;                   // /2 -> 168 MHz
constexpr uint32_t kPllQ = 7;                   // /7 -> 48 MHz
constexpr uint32_t kWaitStates168MHz = 5;

void fall_back_to_hsi(rcc::Registers& r) {
  r.CR = r.CR | rcc::kCrHsiOn;
  wait_set(r.CR, rcc::kCrHsiRdy, rcc::kCrHsiRdy);
  r.CFGR = field(rcc::kSwHsi, rcc::kCfgrSw);  // HSI, every prescaler /1
  wait_set(r.CFGR, mask(2, rcc::kCfgrSws), field(rcc::kSwHsi, rcc::kCfgrSws));
  r.CR = r.CR & ~(rcc::kCrPllOn | rcc::kCrHseOn);
}

}  // namespace

Clocks configure_clocks() {
  rcc::Registers& r = rcc::regs();
  Clocks hsi;
  // Out of reset the core runs on HSI with HSIRDY set; an RCC that shows neither is not there.
  if ((r.CR & (rcc::kCrHsiOn | rcc::kCrHsiRdy)) == 0) {
    hsi.source = ClockSource::kUnreadable;
    hsi.apb1_timer_hz = kEmulatorTimerHz;
    hsi.apb2_timer_hz = kEmulatorTimerHz;
    return hsi;
  }

  r.CR = r.CR | rcc::kCrHseOn;
  if (!wait_set(r.CR, rcc::kCrHseRdy, rcc::kCrHseRdy)) {
    fall_back_to_hsi(r);
    return hsi;
  }
  r.CR = r.CR & ~rcc::kCrPllOn;
  wait_set(r.CR, rcc::kCrPllRdy, 0);
  r.PLLCFGR = field(kPllM, rcc::kPllM) | field(kPllN, rcc::kPllN) | field(kPllP, rcc::kPllP) |
              rcc::kPllSrcHse | field(kPllQ, rcc::kPllQ);
  r.CR = r.CR | rcc::kCrPllOn;
  if (!wait_set(r.CR, rcc::kCrPllRdy, rcc::kCrPllRdy)) {
    fall_back_to_hsi(r);
    return hsi;
  }

  // Wait states before the clock rises; read back, as RM0090 §3.5.1 asks.
  flash_if::Registers& f = flash_if::regs();
  f.ACR = field(kWaitStates168MHz, flash_if::kAcrLatency) | flash_if::kAcrPrften |
          flash_if::kAcrIcen | flash_if::kAcrDcen;
  if ((f.ACR & mask(3, flash_if::kAcrLatency)) != kWaitStates168MHz) {
    fall_back_to_hsi(r);
    return hsi;
  }
  r.CFGR = field(rcc::kPpreDiv4, rcc::kCfgrPpre1) | field(rcc::kPpreDiv2, rcc::kCfgrPpre2) |
           field(rcc::kSwPll, rcc::kCfgrSw);
  if (!wait_set(r.CFGR, mask(2, rcc::kCfgrSws), field(rcc::kSwPll, rcc::kCfgrSws))) {
    fall_back_to_hsi(r);
    return hsi;
  }

  Clocks pll;
  pll.source = ClockSource::kPll;
  pll.sysclk_hz = 168'000'000;
  pll.apb1_hz = 42'000'000;
  pll.apb2_hz = 84'000'000;
  pll.apb1_timer_hz = 84'000'000;  // an APB prescaler above 1 doubles the timer clock
  pll.apb2_timer_hz = 168'000'000;
  pll.usb_clock_ok = true;
  return pll;
}

}  // namespace tetrapulse::stm32f405
