#include "tetrapulse/sim/flicker_emitter.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse::sim {

double FlickerEmitter::integral_cycles(double c) const {
  if (flicker_.kind == Flicker::Kind::kSquare) {
    const double whole = std::floor(c);
    return whole * flicker_.duty + std::min(c - whole, flicker_.duty);
  }
  // sine: integral of 1 - depth/2 + depth/2 cos(2 pi c)
  return c * (1.0 - flicker_.depth / 2) + flicker_.depth / 2 * std::sin(2 * M_PI * c) / (2 * M_PI);
}

double FlickerEmitter::do_mean_emission(int, int64_t t0_ns, int64_t t1_ns) const {
  if (flicker_.kind == Flicker::Kind::kSteady || !(flicker_.frequency_hz > 0) || t1_ns <= t0_ns) return 1.0;
  // Cycles counted from the start of the window's cycle so that large times keep precision.
  const double f = flicker_.frequency_hz * 1e-9;  // cycles per ns
  const double c0 = static_cast<double>(t0_ns) * f + flicker_.phase;
  const double base = std::floor(c0);
  const double a = c0 - base;
  const double b = a + static_cast<double>(t1_ns - t0_ns) * f;
  return (integral_cycles(b) - integral_cycles(a)) / (b - a);
}

}  // namespace tetrapulse::sim
