#include "tetrapulse/sim/occluded_emitter.hpp"

namespace tetrapulse::sim {

double OccludedEmitter::do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const {
  if (t1_ns <= t0_ns) return 0.0;
  if (index < 0 || static_cast<size_t>(index) >= hidden_.size() || hidden_[static_cast<size_t>(index)].empty()) {
    return inner_->mean_emission(index, t0_ns, t1_ns);
  }
  double total = 0;
  hidden_[static_cast<size_t>(index)].split(t0_ns, t1_ns, [&](int64_t a, int64_t b, bool hidden) {
    if (!hidden) total += inner_->mean_emission(index, a, b) * static_cast<double>(b - a);
  });
  return total / static_cast<double>(t1_ns - t0_ns);
}

}  // namespace tetrapulse::sim
