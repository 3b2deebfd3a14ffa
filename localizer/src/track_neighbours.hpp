#pragma once
// Internal to TargetIdentifier: which candidate tracks lie close enough to be markers
// of one target. A target's four markers lie within its image size of each other, so
// enumerating a target's hypotheses needs, for each track, only the tracks within
// reach of it: with N tracks of N / 4 targets, all pairs is O(N^2) a target and
// O(N^3) over the swarm; the lists below make it linear in the targets (a track has
// about as many neighbours however many targets fly).
//
// Track j is a neighbour of track i (j != i) when
//   |p_i - p_j| <= reach(max(r_i, r_j)),
// p pixels, r blob radii (pixels), reach() increasing in the radius: the largest reach
// of any target, so that every pair near for one target is among them. Each list is
// in increasing track index, the order the enumeration visits candidates in.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tetrapulse/localizer/target_identifier.hpp"

namespace tetrapulse::localizer_internal {

class TrackNeighbours {
 public:
  // reach(radius_px) -> pixels, non-decreasing in radius_px.
  template <class Reach>
  void find(const std::vector<CandidateTrack>& tracks, Reach reach) {
    double largest_radius = 0;
    for (const CandidateTrack& c : tracks)
      if (c.radius_px > largest_radius) largest_radius = c.radius_px;
    sweep(tracks, reach(largest_radius), [&](size_t i, size_t j, double distance) {
      // fmax: a radius that is not a number leaves the other's (the caller's test
      // takes the first track's radius then, whichever comes first).
      return distance <= reach(std::fmax(tracks[i].radius_px, tracks[j].radius_px));
    });
  }

  // Neighbours of track i, by increasing index.
  const std::vector<int>& of(size_t i) const { return lists_[i]; }

 private:
  // Pairs within `strip` pixels in x, sorted along x; `keep(i, j, distance)` decides.
  template <class Keep>
  void sweep(const std::vector<CandidateTrack>& tracks, double strip, Keep keep);

  std::vector<std::vector<int>> lists_;
  std::vector<int> by_x_;
};

template <class Keep>
void TrackNeighbours::sweep(const std::vector<CandidateTrack>& tracks, double strip, Keep keep) {
  const size_t n = tracks.size();
  lists_.resize(n);
  for (auto& list : lists_) list.clear();
  // Tracks sorted by x, each compared with those ahead of it within the strip; one
  // whose pixel is not finite (no order along x) with every other.
  if (std::isnan(strip)) strip = std::numeric_limits<double>::infinity();
  by_x_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (tracks[i].pixel.allFinite()) {
      by_x_.push_back(int(i));
      continue;
    }
    for (size_t j = 0; j < n; ++j)
      if (j != i && (tracks[j].pixel.allFinite() || j > i) &&
          keep(i, j, (tracks[i].pixel - tracks[j].pixel).norm()))
        lists_[i].push_back(int(j)), lists_[j].push_back(int(i));
  }
  std::sort(by_x_.begin(), by_x_.end(),
            [&](int a, int b) { return tracks[size_t(a)].pixel.x() < tracks[size_t(b)].pixel.x(); });
  for (size_t k = 0; k < by_x_.size(); ++k) {
    const size_t i = size_t(by_x_[k]);
    for (size_t l = k + 1; l < by_x_.size(); ++l) {
      const size_t j = size_t(by_x_[l]);
      if (!(tracks[j].pixel.x() - tracks[i].pixel.x() <= strip)) break;
      if (!keep(i, j, (tracks[i].pixel - tracks[j].pixel).norm())) continue;
      lists_[i].push_back(int(j));
      lists_[j].push_back(int(i));
    }
  }
  for (auto& list : lists_) std::sort(list.begin(), list.end());
}

}  // namespace tetrapulse::localizer_internal
