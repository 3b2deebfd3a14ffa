#pragma once
// A lamp that is not one of ours (a distractor): steady, a square wave (a PWM
// LED, a blinking indicator) or a sinusoid (a mains-powered lamp), in rig time.
//   steady: e(t) = 1
//   square: e(t) = 1 while frac(f t + phase) < duty, else 0
//   sine:   e(t) = 1 - depth (1 - cos(2 pi (f t + phase))) / 2
// with t in seconds of rig time, f in Hz and phase in cycles. The mean over a
// window is computed in closed form.
#include "tetrapulse/sim/led_emitter.hpp"

namespace tetrapulse::sim {

struct Flicker {
  enum class Kind { kSteady, kSquare, kSine };
  Kind kind = Kind::kSteady;
  double frequency_hz = 0;
  double duty = 0.5;    // square: fraction of each cycle that is on, (0, 1]
  double depth = 1.0;   // sine: 0 (steady) to 1 (fully dark at the trough)
  double phase = 0.0;   // cycles, [0, 1)
};

class FlickerEmitter : public LedEmitter {
 public:
  explicit FlickerEmitter(const Flicker& flicker) : flicker_(flicker) {}

 private:
  double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const override;
  // Integral of e over [0, cycles) in units of cycles.
  double integral_cycles(double cycles) const;

  Flicker flicker_;
};

}  // namespace tetrapulse::sim
