#include "target_clock.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tetrapulse::localizer_internal {

void TargetClock::start(const CodeClock& identified, int64_t mid_ns) {
  clock_ = identified;
  checked_ns_ = mid_ns;
  identified_ns_ = mid_ns;
  identified_origin_ns_ = identified.origin_ns;
  origin_drift_.emplace_back(0.0, 0.0);
}

void TargetClock::forget() {
  origin_drift_.clear();
  rate_ = 1.0;
}

CodeClock TargetClock::estimated() const {
  CodeClock c = clock_;
  c.rate = rate_;
  const double tau = double(checked_ns_);
  c.origin_ns = int64_t(std::llround(tau - (tau - double(clock_.origin_ns)) / rate_));
  return c;
}

void TargetClock::refit(int64_t mid_ns, uint32_t code_length, const std::function<double(const CodeClock&)>& cost) {
  const int64_t T = clock_.bit_period_ns;
  if (mid_ns - checked_ns_ < int64_t(code_length) * T) return;
  checked_ns_ = mid_ns;
  constexpr int kSteps = 16;
  std::array<double, 2 * kSteps + 1> costs{};
  for (int k = -kSteps; k <= kSteps; ++k) {
    CodeClock candidate = clock_;
    candidate.rate = 1.0;
    candidate.origin_ns = clock_.origin_ns + k * T / (2 * kSteps);
    costs[size_t(k + kSteps)] = cost(candidate);
  }
  const double best = *std::min_element(costs.begin(), costs.end());
  int first = -1, last = -1;
  for (int k = 0; k <= 2 * kSteps; ++k)
    if (costs[size_t(k)] == best) {
      if (first < 0) first = k;
      last = k;
    }
  const int k = (first + last) / 2 - kSteps;
  clock_.origin_ns += k * T / (2 * kSteps);
  const double since = double(mid_ns - identified_ns_) * 1e-9;
  origin_drift_.emplace_back(since, double(clock_.origin_ns - identified_origin_ns_));
  if (origin_drift_.size() >= 3 && since >= 2.0) {
    double st = 0, so = 0, stt = 0, sto = 0;
    for (const auto& [s, o] : origin_drift_) st += s, so += o, stt += s * s, sto += s * o;
    const double n = double(origin_drift_.size());
    const double slope_ns_per_s = (n * sto - st * so) / (n * stt - st * st);
    rate_ = 1.0 - std::clamp(slope_ns_per_s * 1e-9, -200e-6, 200e-6);
  }
}

}  // namespace tetrapulse::localizer_internal
