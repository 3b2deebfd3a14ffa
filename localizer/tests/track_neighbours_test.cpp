// TrackNeighbours (the enumeration's candidate pairs) against its definition, pair by
// pair: random crowds of tracks, with pixels and radii that are not numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../src/track_neighbours.hpp"

namespace tetrapulse::localizer_internal {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// j is i's neighbour iff j != i and |p_i - p_j| <= reach(fmax(r_i, r_j)).
std::vector<int> by_definition(const std::vector<CandidateTrack>& tracks, size_t i, double extent) {
  std::vector<int> out;
  for (size_t j = 0; j < tracks.size(); ++j) {
    if (j == i) continue;
    const double r = std::fmax(tracks[i].radius_px, tracks[j].radius_px);
    if ((tracks[i].pixel - tracks[j].pixel).norm() <= 2 * extent * std::max(r, 0.0) + 10) out.push_back(int(j));
  }
  return out;
}

std::vector<CandidateTrack> crowd(std::mt19937_64& rng, size_t n, bool odd_values) {
  std::uniform_real_distribution<double> x(0, 1280), y(0, 960), radius(0.3, 6);
  std::uniform_int_distribution<int> odd(0, 19);
  std::vector<CandidateTrack> tracks(n);
  for (CandidateTrack& c : tracks) {
    c.pixel = {x(rng), y(rng)};
    c.radius_px = radius(rng);
    if (!odd_values) continue;
    switch (odd(rng)) {
      case 0: c.pixel.x() = kNaN; break;
      case 1: c.pixel.y() = kInf; break;
      case 2: c.radius_px = kNaN; break;
      case 3: c.radius_px = -2; break;
      case 4: c.pixel = tracks.front().pixel; break;  // on top of another
      default: break;
    }
  }
  return tracks;
}

TEST(TrackNeighbours, ListsExactlyTheTracksWithinReachInIndexOrder) {
  std::mt19937_64 rng(17);
  TrackNeighbours neighbours;
  int64_t pairs = 0, all_pairs = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const size_t n = size_t(std::uniform_int_distribution<int>(0, 300)(rng));
    const double extent = std::uniform_real_distribution<double>(1, 12)(rng);
    const std::vector<CandidateTrack> tracks = crowd(rng, n, trial % 2 == 1);
    neighbours.find(tracks, [extent](double r) { return 2 * extent * std::max(r, 0.0) + 10; });
    for (size_t i = 0; i < n; ++i) {
      const std::vector<int> expected = by_definition(tracks, i, extent);
      ASSERT_EQ(neighbours.of(i), expected) << "trial " << trial << ", track " << i << " of " << n;
      pairs += int64_t(expected.size());
    }
    all_pairs += int64_t(n) * int64_t(n > 0 ? n - 1 : 0);
  }
  // The crowds are dense enough that most tracks have neighbours and sparse enough
  // that the strip matters.
  EXPECT_GT(pairs, 50000);
  EXPECT_LT(pairs, all_pairs / 2);
}

TEST(TrackNeighbours, InfiniteReachMakesEveryTrackANeighbour) {
  std::mt19937_64 rng(3);
  const std::vector<CandidateTrack> tracks = crowd(rng, 40, false);
  TrackNeighbours neighbours;
  neighbours.find(tracks, [](double) { return kInf; });
  for (size_t i = 0; i < tracks.size(); ++i) EXPECT_EQ(neighbours.of(i).size(), tracks.size() - 1);
}

TEST(TrackNeighbours, ListsFromAnEarlierCallAreReplaced) {
  std::mt19937_64 rng(5);
  TrackNeighbours neighbours;
  neighbours.find(crowd(rng, 200, false), [](double) { return 500.0; });
  const std::vector<CandidateTrack> few = crowd(rng, 3, false);
  neighbours.find(few, [](double) { return 0.0; });
  for (size_t i = 0; i < few.size(); ++i) EXPECT_TRUE(neighbours.of(i).empty());
}

}  // namespace
}  // namespace tetrapulse::localizer_internal
