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
  explicit NoiseSampler(uint64_t seed);

  double normal() { return normal_from(rng_); }
  // n deviates at once (the same as n calls of normal(), faster: the generator stays in registers).
  void fill_normal(float* out, int n) {
    Random rng = rng_;
    for (int i = 0; i < n; ++i) out[i] = static_cast<float>(normal_from(rng));
    rng_ = rng;
  }
  int poisson(double mean);
  double uniform() { return rng_.uniform(); }

  static constexpr int kCellBits = 12;
  static constexpr uint32_t kCells = 1u << kCellBits;

 private:
  static constexpr uint32_t kFracMask = (1u << (32 - kCellBits)) - 1;
  double normal_from(Random& rng) const {
    const auto u = static_cast<uint32_t>(rng.next() >> 32);
    const uint32_t cell = u >> (32 - kCellBits);
    if (cell == 0 || cell == kCells - 1) return tail(u);
    const double frac = (static_cast<double>(u & kFracMask) + 0.5) * (1.0 / (kFracMask + 1.0));
    const double a = table_[cell], b = table_[cell + 1];
    return a + frac * (b - a);
  }
  static double tail(uint32_t u);

  Random rng_;
  const double* table_;  // Phi^-1(i / kCells), i = 1 .. kCells - 1 (shared, built once)
};

}  // namespace tetrapulse::sim
