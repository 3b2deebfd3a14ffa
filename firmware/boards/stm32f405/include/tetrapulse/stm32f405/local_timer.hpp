#pragma once
// TIM2, the board's local clock: a 32-bit up-counter at the APB1 timer clock (84 MHz on
// the PLL), extended to 64 bits in software by counting overflows in its update interrupt.
//
// Its channels:
//   CH1  output compare, no pin: CNT == CCR1 pulses TRGO (master mode "compare pulse"),
//        which TIM8 takes as a reset trigger to apply LED levels at that exact tick
//        (led_timer.hpp). No interrupt: TIM8's update interrupt reports it.
//   CH2  input capture on the sync input (pinout.hpp): edges are time-stamped by hardware
//        to the tick and extended to 64 bits in the interrupt.
#include <cstdint>

#include "tetrapulse/fw/clock/local_clock.hpp"

namespace tetrapulse::stm32f405 {

class LocalTimer final : public fw::LocalClock {
 public:
  using CaptureCallback = void (*)(void* context, uint64_t tick);

  // Fastest tick: with it the 32-bit counter wraps every 51 s or more.
  static constexpr uint32_t kMaxTickHz = 84'000'000;

  // Starts the counter from `timer_clock_hz`, the APB1 timer clock configure_clocks()
  // reported, divided down to at most kMaxTickHz (84 MHz and 16 MHz run undivided).
  void start(uint32_t timer_clock_hz);

  // (now() and tick_hz() come from fw::LocalClock.)
  // Ticks since start(), 64 bits: wraps after 6900 years at 84 MHz. Any context.
  // (Under QEMU 7.2 the update interrupt misbehaves after the first 32-bit wrap, 51 s
  // after start: its timer model truncates its tick count. Emulator runs stay shorter.)
  uint64_t read() const;
  // The 64-bit tick of a 32-bit counter value seen at most 2^31 ticks ago (25 s at 84 MHz).
  uint64_t extend_past(uint32_t counter_value) const;

  // CH2 capture of the sync input; `falling` selects the edge. The callback runs in the
  // timer interrupt with the edge's tick.
  void enable_capture(bool falling, CaptureCallback callback, void* context);
  void disable_capture();

  // CH1 compare: at tick `at` (less than 2^31 ticks ahead) TRGO pulses. Returns false
  // when `at` is not ahead of the counter any more (the pulse would come a wrap later).
  bool arm_compare(uint64_t at);

  // Called from TIM2_IRQHandler.
  void on_interrupt();

 private:
  fw::Tick do_now() const override { return read(); }
  uint32_t do_tick_hz() const override { return tick_hz_; }

  uint32_t tick_hz_ = 0;
  volatile uint32_t high_ = 0;  // overflows counted so far
  CaptureCallback capture_ = nullptr;
  void* capture_context_ = nullptr;
};

// The one instance, bound to TIM2_IRQHandler.
LocalTimer& local_timer();

}  // namespace tetrapulse::stm32f405
