#pragma once
// Fast, platform-independent normal and Poisson deviates for sensor noise.
//   normal():  N(0, 1) by inverting the normal CDF: 12 bits pick one of 4096
//              equal-probability cells, 20 more interpolate inside it (error below
//              1e-3 sigma); the two outermost cells are inverted exactly.
//   poisson(): exact by sequential inversion of the CDF; meant for means < ~30
//              (cost grows with the mean).
#include <cstdint>

#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {

// Phi^-1(p) for p in (0, 1), to about 1e-12 (Newton on erfc).
double inverse_normal_cdf(double p);

class NoiseSampler {
 public:
  explicit NoiseSampler(uint64_t seed) : rng_(seed) {}

  double normal();
  int poisson(double mean);
  double uniform() { return rng_.uniform(); }

 private:
  Random rng_;
};

}  // namespace tetrapulse::sim
