#include "tetrapulse/sim/noise_sampler.hpp"

#include <array>
#include <cmath>

namespace tetrapulse::sim {

double inverse_normal_cdf(double p) {
  if (!(p > 0 && p < 1)) return p <= 0 ? -INFINITY : INFINITY;
  // Start on the tail side of the root (|z0| >= |z|), from where Newton on the
  // log-concave CDF converges monotonically.
  const double q = p < 0.5 ? p : 1 - p;
  double z = std::sqrt(-2 * std::log(q));
  if (p < 0.5) z = -z;
  for (int it = 0; it < 100; ++it) {
    const double cdf = 0.5 * std::erfc(-z / M_SQRT2);
    const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI);
    if (!(pdf > 0)) break;
    const double step = (cdf - p) / pdf;
    z -= step;
    if (std::abs(step) < 1e-13 * (1 + std::abs(z))) break;
  }
  return z;
}

namespace {

// table[i] = Phi^-1(i / kCells), i = 1 .. kCells - 1.
const std::array<double, NoiseSampler::kCells>& quantile_table() {
  static const std::array<double, NoiseSampler::kCells> table = [] {
    std::array<double, NoiseSampler::kCells> t{};
    for (uint32_t i = 1; i < NoiseSampler::kCells; ++i) t[i] = inverse_normal_cdf(static_cast<double>(i) / NoiseSampler::kCells);
    return t;
  }();
  return table;
}

}  // namespace

NoiseSampler::NoiseSampler(uint64_t seed) : rng_(seed), table_(quantile_table().data()) {}

// The two outermost cells, where the quantile is too steep to interpolate: exactly.
double NoiseSampler::tail(uint32_t u) { return inverse_normal_cdf((static_cast<double>(u) + 0.5) * 0x1.0p-32); }

int NoiseSampler::poisson(double mean) {
  if (!(mean > 0)) return 0;
  const double u = rng_.uniform();
  double p = std::exp(-mean);
  double cdf = p;
  int k = 0;
  while (u > cdf && k < 100000) {
    ++k;
    p *= mean / k;
    cdf += p;
    if (p == 0 && k > mean) break;  // the tail no longer adds anything representable
  }
  return k;
}

}  // namespace tetrapulse::sim
