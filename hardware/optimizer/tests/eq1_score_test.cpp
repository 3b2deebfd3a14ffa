#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tetrapulse/hardware/eq1_score.hpp"

namespace tetrapulse::hardware {
namespace {

// s_min and s_avg straight from the definition: every pair.
DistanceSpread all_pairs(const std::vector<double>& d) {
  double smallest = INFINITY, sum = 0;
  int pairs = 0;
  for (size_t a = 0; a < d.size(); ++a) {
    for (size_t b = a + 1; b < d.size(); ++b) {
      smallest = std::min(smallest, std::abs(d[a] - d[b]));
      sum += std::abs(d[a] - d[b]);
      ++pairs;
    }
  }
  return pairs ? DistanceSpread{smallest, sum / pairs} : DistanceSpread{};
}

rc::Gen<std::vector<double>> gen_distances(int min_size, int max_size) {
  return rc::gen::mapcat(rc::gen::inRange(min_size, max_size + 1), [](int n) {
    return rc::gen::container<std::vector<double>>(
        static_cast<size_t>(n), rc::gen::map(rc::gen::inRange(15000, 30001), [](int v) { return v * 1e-5; }));
  });
}

RC_GTEST_PROP(DistancePool, SpreadWithMovingDistancesEqualsAllPairs, ()) {
  const std::vector<double> fixed = *gen_distances(0, 60);
  const std::vector<double> moving = *gen_distances(1, 12);
  std::vector<double> all = fixed;
  all.insert(all.end(), moving.begin(), moving.end());
  const DistanceSpread expected = all_pairs(all);
  const DistanceSpread got = DistancePool(fixed).spread_with(moving.data(), static_cast<int>(moving.size()));
  if (all.size() < 2) {
    RC_ASSERT(got.s_min == 0.0 && got.s_avg == 0.0);
  } else {
    RC_ASSERT(std::abs(got.s_min - expected.s_min) < 1e-12);
    RC_ASSERT(std::abs(got.s_avg - expected.s_avg) < 1e-12);
  }
  const DistanceSpread whole = distance_spread(all);
  RC_ASSERT(std::abs(whole.s_min - got.s_min) < 1e-12);
  RC_ASSERT(std::abs(whole.s_avg - got.s_avg) < 1e-12);
}

TEST(Eq1, EvenlySpacedDistancesReachTheBound) {
  const Eq1Limits l;
  std::vector<double> d;
  for (int i = 0; i < 6; ++i) d.push_back(l.d1 + i * (l.d2 - l.d1) / 5);
  const DistanceSpread s = distance_spread(d);
  EXPECT_NEAR(s.s_min, (l.d2 - l.d1) / 5, 1e-15);
  // Pairs k apart (k = 1..5) number 6 - k: mean gap count 35 / 15.
  EXPECT_NEAR(s.s_avg, (l.d2 - l.d1) / 5 * 35.0 / 15.0, 1e-15);
}

RC_GTEST_PROP(Eq1, EveryInfeasibleSystemScoresBelowEveryFeasibleOne, ()) {
  const Eq1Limits l;
  const std::vector<double> d = *gen_distances(2, 30);
  const double violation = *rc::gen::inRange(1, 100000) * 1e-9;
  const DistanceSpread s = distance_spread(d);
  RC_ASSERT(eq1_value(s, violation, l) < 0.0);
  RC_ASSERT(eq1_value(s, 0.0, l) >= 0.0);
  RC_ASSERT(eq1_value(s, violation, l) < eq1_value(s, violation / 2, l));  // less violation is better
}

TEST(Eq1, ScoresEveryConstraintOfEveryTarget) {
  const Eq1Limits l;
  const TargetShape fine{{0.15, 0.18, 0.21, 0.24, 0.27, 0.30}, 0.13};
  TargetShape too_long = fine;
  too_long.distances[5] = 0.31;
  TargetShape too_flat = fine;
  too_flat.face_height = 0.11;
  EXPECT_EQ(eq1_score({fine}, l).violation, 0.0);
  EXPECT_NEAR(eq1_score({fine, too_long}, l).violation, 0.01, 1e-15);
  EXPECT_NEAR(eq1_score({too_flat, fine, too_long}, l).violation, 0.02, 1e-15);
  EXPECT_LT(eq1_score({fine, too_long}, l).f, 0.0);
}

// Evenly spaced distances against the two-cluster layout that trades s_min for s_avg
// (every gap 0 but the middle one): the evenly spaced ones win exactly above
// clustering_weight(N), and default_weight(N) sits above it.
RC_GTEST_PROP(Eq1, EvenSpacingWinsExactlyAboveTheClusteringWeight, ()) {
  const int n = *rc::gen::inRange(3, 120);
  const double threshold = clustering_weight(n);
  std::vector<double> even, clustered;
  for (int i = 0; i < n; ++i) {
    even.push_back(0.15 + 0.15 * i / (n - 1));
    clustered.push_back(i < n / 2 ? 0.15 : 0.30);
  }
  const auto f = [](const std::vector<double>& d, double w) {
    return eq1_value(distance_spread(d), 0.0, Eq1Limits{0.15, 0.30, 0.12, w});
  };
  if (n % 2 == 0) {  // with an odd count the middle distance cannot split evenly: threshold is a bound only
    RC_ASSERT(f(even, threshold + 1e-3) > f(clustered, threshold + 1e-3));
    RC_ASSERT(f(even, threshold - 1e-3) < f(clustered, threshold - 1e-3));
  }
  RC_ASSERT(f(even, default_weight(n)) > f(clustered, default_weight(n)));
  RC_ASSERT(default_weight(n) > threshold);
}

TEST(Eq1, DefaultWeightIsThePapersForOneTarget) { EXPECT_DOUBLE_EQ(default_weight(6), 2.0 / 3.0); }

}  // namespace
}  // namespace tetrapulse::hardware
