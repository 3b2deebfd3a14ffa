#include "tetrapulse/hardware/eq1_score.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tetrapulse::hardware {

namespace {

// Sum of |a - b| over the pairs of sorted values: each x_k is the larger of k pairs
// and the smaller of (n - 1 - k).
double sorted_pair_sum(const double* x, int n) {
  double sum = 0;
  for (int k = 0; k < n; ++k) sum += (2.0 * k - (n - 1)) * x[k];
  return sum;
}

double sorted_min_gap(const double* x, int n) {
  double gap = INFINITY;
  for (int k = 1; k < n; ++k) gap = std::min(gap, x[k] - x[k - 1]);
  return gap;
}

}  // namespace

DistancePool::DistancePool(std::vector<double> fixed) : sorted_(std::move(fixed)) {
  std::sort(sorted_.begin(), sorted_.end());
  prefix_.assign(sorted_.size() + 1, 0.0);
  for (size_t k = 0; k < sorted_.size(); ++k) prefix_[k + 1] = prefix_[k] + sorted_[k];
  pair_sum_ = sorted_pair_sum(sorted_.data(), size());
  min_gap_ = sorted_min_gap(sorted_.data(), size());
}

DistanceSpread DistancePool::spread_with(const double* moving, int count) const {
  // The moving set is one target's six distances in the optimiser; larger sets
  // (whole systems, in checks and tests) take a heap buffer.
  std::array<double, 8> small{};
  std::vector<double> large;
  double* x = small.data();
  if (count > static_cast<int>(small.size())) {
    large.assign(moving, moving + count);
    x = large.data();
  } else {
    std::copy(moving, moving + count, x);
  }
  std::sort(x, x + count);

  const int m = size();
  const double total = prefix_[m];
  double pair_sum = pair_sum_ + sorted_pair_sum(x, count);
  double gap = std::min(min_gap_, sorted_min_gap(x, count));
  for (int i = 0; i < count; ++i) {
    const int k = static_cast<int>(std::lower_bound(sorted_.begin(), sorted_.end(), x[i]) - sorted_.begin());
    pair_sum += x[i] * k - prefix_[k] + (total - prefix_[k]) - x[i] * (m - k);
    if (k > 0) gap = std::min(gap, x[i] - sorted_[k - 1]);
    if (k < m) gap = std::min(gap, sorted_[k] - x[i]);
  }
  const double n = m + count;
  if (n < 2) return {};
  return DistanceSpread{gap, pair_sum / (n * (n - 1) / 2)};
}

DistanceSpread distance_spread(const std::vector<double>& distances) {
  return DistancePool().spread_with(distances.data(), static_cast<int>(distances.size()));
}

double range_violation(const double* distances, int count, double lo, double hi) {
  double v = 0;
  for (int i = 0; i < count; ++i) {
    if (distances[i] < lo) v += lo - distances[i];
    if (distances[i] > hi) v += distances[i] - hi;
  }
  return v;
}

double shape_violation(const TargetShape& target, const Eq1Limits& limits) {
  return range_violation(target.distances.data(), 6, limits.d1, limits.d2) +
         height_violation(target.face_height, limits.h);
}

Eq1Score eq1_score(const std::vector<TargetShape>& targets, const Eq1Limits& limits) {
  Eq1Score score;
  std::vector<double> all;
  for (const TargetShape& t : targets) {
    all.insert(all.end(), t.distances.begin(), t.distances.end());
    score.violation += shape_violation(t, limits);
  }
  score.spread = distance_spread(all);
  score.f = eq1_value(score.spread, score.violation, limits);
  return score;
}

}  // namespace tetrapulse::hardware
