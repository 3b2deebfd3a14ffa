#pragma once
// What the renderer asks of a light: how bright it was, on average, over a window
// of rig time. The renderer multiplies this by the light's radiance and the
// window's length, so any model of the light (the contract's code formula, the
// firmware's code player on a simulated board, a flickering lamp) plugs in here.
#include <cstdint>

namespace tetrapulse::sim {

class LedEmitter {
 public:
  virtual ~LedEmitter() = default;

  // Mean relative emission, 0 (dark) to 1 (full), of light `index` (a marker 0..3,
  // or 0 for a single lamp) over the rig-time window [t0_ns, t1_ns), t0_ns < t1_ns.
  double mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const { return do_mean_emission(index, t0_ns, t1_ns); }

 private:
  virtual double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const = 0;
};

}  // namespace tetrapulse::sim
