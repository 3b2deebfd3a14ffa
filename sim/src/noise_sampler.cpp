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

constexpr int kCellBits = 12;
constexpr int kCells = 1 << kCellBits;

// table[i] = Phi^-1(i / kCells), i = 1 .. kCells - 1.
const std::array<double, kCells>& quantile_table() {
  static const std::array<double, kCells> table = [] {
    std::array<double, kCells> t{};
    for (int i = 1; i < kCells; ++i) t[static_cast<size_t>(i)] = inverse_normal_cdf(static_cast<double>(i) / kCells);
    return t;
  }();
  return table;
}

}  // namespace

double NoiseSampler::normal() {
  const auto& table = quantile_table();
  const auto u = static_cast<uint32_t>(rng_.next() >> 32);
  const uint32_t cell = u >> (32 - kCellBits);
  if (cell == 0 || cell == kCells - 1) return inverse_normal_cdf((static_cast<double>(u) + 0.5) * 0x1.0p-32);
  const double frac = (static_cast<double>(u & ((1u << (32 - kCellBits)) - 1)) + 0.5) * 0x1.0p-20;
  const double a = table[cell], b = table[cell + 1];
  return a + frac * (b - a);
}

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
