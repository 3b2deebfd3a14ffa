#pragma once
// Hardware seam: the board's free-running local counter, extended to 64 bits.
//
// The counter runs from the board's crystal, so its true rate is tick_hz() * (1 + e)
// with |e| up to 100 ppm; the clock servo (clock_servo.hpp) maps it to rig time.
// stm32f405: a 32-bit timer (TIM2/TIM5) extended by its overflow interrupt; the same
// counter drives the LED compares and the sync-edge input capture.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"

namespace tetrapulse::fw {

class LocalClock {
 public:
  // The counter now, in ticks. Monotonic.
  Tick now() const { return do_now(); }
  // Nominal tick rate in Hz (the crystal's error is the servo's business).
  uint32_t tick_hz() const { return do_tick_hz(); }

 protected:
  ~LocalClock() = default;

 private:
  virtual Tick do_now() const = 0;
  virtual uint32_t do_tick_hz() const = 0;
};

}  // namespace tetrapulse::fw
