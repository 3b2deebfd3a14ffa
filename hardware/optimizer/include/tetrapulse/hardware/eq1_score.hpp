#pragma once
// The target-distinctness cost of Breitenmoser, Kneip & Siegwart 2011, Sec. III-A, Eq. 1:
//
//   f = w s_min + (1 - w) s_avg   if D1 <= d <= D2 for every marker distance d
//                                  and h_min >= H for every target,
//   f = -G                         otherwise,
//
// with S = { |d_a - d_b| : a < b } over the system's marker distances, s_min = min S,
// s_avg = mean S. All lengths in metres.
//
// Which distances: the paper defines S over "all markers and targets". Distances
// between markers of *different* targets change as the robots move and carry no
// geometry, so the system's distances are the 6 n distances within the n targets,
// and every pair of them enters S: two distances of one target (markers must be told
// apart) and one distance from each of two targets (targets must be told apart).
// Six distances in [D1, D2] give s_min <= (D2 - D1) / 5; 6 n give (D2 - D1) / (6 n - 1).
//
// Deviation from the paper: an infeasible point scores -G - v, v the total constraint
// violation in metres (sum of how far each distance leaves [D1, D2] and each target's
// h_min falls short of H), instead of a flat -G, so a simplex started outside the
// constraints walks into them. G = D2 - D1 > 0 and feasible f >= 0, so every
// infeasible point still scores below every feasible one.
#include <vector>

#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

struct Eq1Limits {
  double d1 = 0.15;           // D1, shortest allowed marker distance (m)
  double d2 = 0.30;           // D2, longest allowed marker distance (m)
  double h = 0.12;            // H, smallest allowed face height (m), tetrahedron.hpp
  double w = 2.0 / 3.0;       // weight of s_min against s_avg, [0, 1]
};

// s_min and s_avg of S for a set of distances; both 0 with fewer than two distances.
struct DistanceSpread {
  double s_min = 0;
  double s_avg = 0;
};

// Distances held fixed while a few others move (one target at a time): the spread of
// fixed + moving costs O(k log M) for k moving among M fixed, instead of O(M log M).
class DistancePool {
 public:
  DistancePool() : DistancePool(std::vector<double>{}) {}
  explicit DistancePool(std::vector<double> fixed);

  DistanceSpread spread_with(const double* moving, int count) const;
  int size() const { return static_cast<int>(sorted_.size()); }

 private:
  std::vector<double> sorted_;
  std::vector<double> prefix_;  // prefix_[k] = sum of sorted_[0..k)
  double pair_sum_ = 0;         // sum of |a - b| over fixed pairs
  double min_gap_ = 0;          // min |a - b| over fixed pairs (infinite with fewer than 2)
};

DistanceSpread distance_spread(const std::vector<double>& distances);

// How far `count` distances leave [lo, hi], summed (m).
double range_violation(const double* distances, int count, double lo, double hi);
// How far a face height falls short of `least` (m).
inline double height_violation(double height, double least) { return height < least ? least - height : 0.0; }

// One target as Eq. 1 sees it: its six marker distances and its face height (for
// a 3D target min_face_height; for a projection min_triangle_altitude).
struct TargetShape {
  Edges distances{};
  double face_height = 0;
};

// A target of four markers in space, and four markers in a plane (a projection,
// whose face height is its smallest triangle altitude: its volume is zero).
inline TargetShape solid_shape(const Edges& e) { return TargetShape{e, min_face_height(e)}; }
inline TargetShape planar_shape(const Edges& e) { return TargetShape{e, min_triangle_altitude(e)}; }

struct Eq1Score {
  double f = 0;          // Eq. 1 (graded penalty when infeasible)
  DistanceSpread spread;  // over all 6 n distances
  double violation = 0;  // 0 when every constraint holds (m)
};

// Eq. 1 for a whole system of targets.
Eq1Score eq1_score(const std::vector<TargetShape>& targets, const Eq1Limits& limits);
// How far one target's distances and face height leave the constraints (m).
double shape_violation(const TargetShape& target, const Eq1Limits& limits);

// The penalty constant G of Eq. 1.
inline double eq1_penalty(const Eq1Limits& limits) { return limits.d2 - limits.d1; }

// Eq. 1 (with the graded penalty above) from the spread and the total violation.
inline double eq1_value(const DistanceSpread& spread, double violation, const Eq1Limits& limits) {
  if (violation > 0) return -eq1_penalty(limits) - violation;
  return limits.w * spread.s_min + (1 - limits.w) * spread.s_avg;
}

// Eq. 1 balances s_min and s_avg differently as the number N of distances grows:
// shifting length from every gap between sorted distances into the middle one trades
// s_min for s_avg, and evenly spaced distances (the best s_min) stay optimal only for
// w > (N - 2) / (N + 4). The paper's w = 2/3 for one target (N = 6) sits at
// w / (1 - w) = 3 (N - 2) / 6, three times that threshold; the default weight keeps
// that margin for any N: w = (N - 2) / N.
inline double clustering_weight(int distances) { return (distances - 2.0) / (distances + 4.0); }
inline double default_weight(int distances) { return (distances - 2.0) / distances; }

}  // namespace tetrapulse::hardware
