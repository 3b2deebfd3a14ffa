#include "tetrapulse/stm32f405/watchdog.hpp"

#include "tetrapulse/stm32f405/registers/iwdg.hpp"

namespace tetrapulse::stm32f405 {
namespace {
constexpr uint32_t kPrescalerDiv64 = 4;   // PR = 4: /64 -> 500 Hz at 32 kHz
constexpr uint32_t kTickMs = 2;
constexpr uint32_t kMaxReload = 0xFFF;
constexpr uint32_t kUpdatePolls = 100'000;  // PVU/RVU clear within a few LSI cycles
}  // namespace

void start_watchdog(uint32_t timeout_ms) {
  iwdg::Registers& w = iwdg::regs();
  uint32_t reload = timeout_ms / kTickMs;
  if (reload > kMaxReload) reload = kMaxReload;
  if (reload == 0) reload = 1;
  w.KR = iwdg::kKeyStart;  // starts the LSI and the counter
  w.KR = iwdg::kKeyUnlock;
  w.PR = kPrescalerDiv64;
  w.RLR = reload;
  for (uint32_t i = 0; i < kUpdatePolls && (w.SR & iwdg::kSrBusy) != 0; ++i) {
  }
  w.KR = iwdg::kKeyReload;
}

void feed_watchdog() { iwdg::regs().KR = iwdg::kKeyReload; }

}  // namespace tetrapulse::stm32f405
