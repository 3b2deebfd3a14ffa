#include "grid_start.hpp"

#include <algorithm>
#include <numeric>

namespace tetrapulse::hardware {

namespace {

using Arrangement = std::array<int, 6>;  // edge e gets the length of rank a[e]

int edge_index(int i, int j) {
  if (i > j) std::swap(i, j);
  for (int e = 0; e < 6; ++e) {
    if (kEdgeMarkers[e][0] == i && kEdgeMarkers[e][1] == j) return e;
  }
  return -1;
}

// One arrangement per class of the 720 under the 24 relabellings of the markers.
std::vector<Arrangement> distinct_arrangements() {
  std::array<int, 4> sigma{0, 1, 2, 3};
  std::vector<std::array<int, 6>> relabel;  // relabel[s][e] = the edge e becomes
  do {
    std::array<int, 6> r{};
    for (int e = 0; e < 6; ++e) r[e] = edge_index(sigma[kEdgeMarkers[e][0]], sigma[kEdgeMarkers[e][1]]);
    relabel.push_back(r);
  } while (std::next_permutation(sigma.begin(), sigma.end()));
  std::vector<Arrangement> classes;
  Arrangement a{0, 1, 2, 3, 4, 5};
  do {
    Arrangement smallest = a;
    for (const auto& r : relabel) {
      Arrangement image{};
      for (int e = 0; e < 6; ++e) image[r[e]] = a[e];
      smallest = std::min(smallest, image);
    }
    if (smallest == a) classes.push_back(a);
  } while (std::next_permutation(a.begin(), a.end()));
  return classes;
}

double tallest_height(const Edges& lengths) { return min_face_height(tallest_arrangement(lengths)); }

}  // namespace

Edges tallest_arrangement(const Edges& lengths) {
  static const std::vector<Arrangement> kArrangements = distinct_arrangements();
  Edges sorted = lengths;
  std::sort(sorted.begin(), sorted.end());
  Edges best = sorted;
  double best_h = -INFINITY;
  for (const Arrangement& a : kArrangements) {
    Edges e{};
    for (int k = 0; k < 6; ++k) e[k] = sorted[a[k]];
    const double h = min_face_height(e);
    if (h > best_h) {
      best_h = h;
      best = e;
    }
  }
  return best;
}

std::vector<Edges> draw_grid_start(const GridStartSettings& s, SeededStream* random) {
  const int dealt = 6 * s.targets;
  const int levels = std::max(s.levels, dealt);
  const double step = (s.limits.d2 - s.limits.d1) / (levels - 1);
  // grid[0 .. dealt) are dealt, six per target; the rest wait undealt.
  std::vector<int> grid(static_cast<size_t>(levels));
  std::iota(grid.begin(), grid.end(), 0);
  for (int i = 0; i < dealt; ++i) std::swap(grid[i], grid[i + random->below(levels - i)]);
  const auto lengths = [&](int t) {
    Edges e{};
    for (int k = 0; k < 6; ++k) e[k] = s.limits.d1 + step * grid[6 * t + k];
    return e;
  };
  std::vector<double> shortfall(static_cast<size_t>(s.targets));
  for (int t = 0; t < s.targets; ++t) shortfall[t] = height_violation(tallest_height(lengths(t)), s.limits.h);
  for (int attempt = 0; attempt < s.swaps * s.targets; ++attempt) {
    const auto worst = std::max_element(shortfall.begin(), shortfall.end());
    if (*worst <= 0) break;
    const int a = static_cast<int>(worst - shortfall.begin());
    const int i = 6 * a + random->below(6);
    int j = random->below(levels - 6);
    if (j >= 6 * a) j += 6;  // any length but target a's own
    const int b = j < dealt ? j / 6 : -1;
    std::swap(grid[i], grid[j]);
    const double new_a = height_violation(tallest_height(lengths(a)), s.limits.h);
    const double new_b = b >= 0 ? height_violation(tallest_height(lengths(b)), s.limits.h) : 0.0;
    if (new_a + new_b < shortfall[a] + (b >= 0 ? shortfall[b] : 0.0)) {
      shortfall[a] = new_a;
      if (b >= 0) shortfall[b] = new_b;
    } else {
      std::swap(grid[i], grid[j]);
    }
  }
  std::vector<Edges> start;
  for (int t = 0; t < s.targets; ++t) start.push_back(tallest_arrangement(lengths(t)));
  return start;
}

}  // namespace tetrapulse::hardware
