#pragma once
// Clock tree: 8 MHz HSE -> PLL (M 8, N 336, P 2, Q 7) -> SYSCLK 168 MHz, USB 48 MHz;
// AHB /1, APB1 /4 (42 MHz, its timers 84 MHz), APB2 /2 (84 MHz, its timers 168 MHz);
// 5 flash wait states (RM0090 table 10, 2.7-3.6 V).
//
// Every wait is bounded. If the crystal or the PLL does not come up, the board stays on
// the 16 MHz HSI with all prescalers at 1, and says so. Under an emulator whose RCC reads
// as zero (QEMU's netduinoplus2) no ready bit ever rises and not even HSIRDY reads back:
// the result is kUnreadable, with the emulator's fixed timer clock (QEMU 7.2 clocks its
// STM32 timers at 1 GHz whatever RCC says).
#include <cstdint>

namespace tetrapulse::stm32f405 {

enum class ClockSource : uint8_t {
  kPll,         // HSE through the PLL, 168 MHz
  kHsi,         // the internal 16 MHz RC oscillator (HSE or PLL failed); USB unusable
  kUnreadable,  // RCC reads back nothing (emulator): frequencies are nominal HSI values
};

// QEMU's stm32f2xx timer model counts at this rate (measured: GetInfo uptime and TIM2
// agree with the host's wall clock in the QEMU test).
constexpr uint32_t kEmulatorTimerHz = 1'000'000'000;

struct Clocks {
  ClockSource source = ClockSource::kHsi;
  uint32_t sysclk_hz = 16'000'000;
  uint32_t apb1_hz = 16'000'000;
  uint32_t apb2_hz = 16'000'000;
  uint32_t apb1_timer_hz = 16'000'000;  // TIM2..7, 12..14
  uint32_t apb2_timer_hz = 16'000'000;  // TIM1, TIM8..11
  bool usb_clock_ok = false;            // 48 MHz from PLLQ
};

// Sets the clock tree up as above; returns what it achieved. Call once, first thing.
Clocks configure_clocks();

}  // namespace tetrapulse::stm32f405
