#include "tetrapulse/protocol/timebase.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tetrapulse::protocol {
namespace {

TEST(TimeBase, BitNumberMatchesTheContractFormula) {
  const TimeBase tb{1'000, 10'000'000};
  EXPECT_EQ(bit_number(tb, 1'000), 0);
  EXPECT_EQ(bit_number(tb, 10'000'999), 0);
  EXPECT_EQ(bit_number(tb, 10'001'000), 1);
  EXPECT_EQ(bit_number(tb, 999), -1);          // just before the epoch
  EXPECT_EQ(bit_number(tb, 1'000 - 10'000'000), -1);
  EXPECT_EQ(bit_number(tb, 1'000 - 10'000'001), -2);
}

TEST(TimeBase, BitIndexWrapsCyclicallyBeforeAndAfterEpoch) {
  const TimeBase tb{0, 100};
  EXPECT_EQ(bit_index(tb, 0, 10), 0u);
  EXPECT_EQ(bit_index(tb, 999, 10), 9u);
  EXPECT_EQ(bit_index(tb, 1000, 10), 0u);
  EXPECT_EQ(bit_index(tb, -1, 10), 9u);
  EXPECT_EQ(bit_index(tb, -1000, 10), 0u);
  EXPECT_EQ(bit_index(tb, -1001, 10), 9u);
}

TEST(TimeBase, NextEdgeIsStrictlyAfterAndABitBoundary) {
  const TimeBase tb{7, 100};
  EXPECT_EQ(next_edge_after(tb, 7), 107);
  EXPECT_EQ(next_edge_after(tb, 106), 107);
  EXPECT_EQ(next_edge_after(tb, 107), 207);
  EXPECT_EQ(next_edge_after(tb, -94), -93);
  EXPECT_EQ(next_edge_after(tb, -93), 7);
}

TEST(TimeBase, StraddlesEdge) {
  const TimeBase tb{0, 100};
  EXPECT_FALSE(straddles_edge(tb, 0, 100));
  EXPECT_TRUE(straddles_edge(tb, 0, 101));
  EXPECT_TRUE(straddles_edge(tb, 99, 2));
  EXPECT_FALSE(straddles_edge(tb, -100, 100));
}

// Property: the functions are inverses of each other over a wide random domain.
TEST(TimeBase, InversesHoldOverRandomInputs) {
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int64_t> time(-(int64_t{1} << 61), int64_t{1} << 61);
  std::uniform_int_distribution<int64_t> period(1, 1'000'000'000);
  std::uniform_int_distribution<uint32_t> length(1, 64);
  int failures = 0;
  for (int i = 0; i < 200000; ++i) {
    const TimeBase tb{time(rng) / 4, period(rng)};
    const int64_t t = time(rng);
    const uint32_t L = length(rng);
    const int64_t n = bit_number(tb, t);
    failures += !(bit_start(tb, n) <= t && t < bit_start(tb, n + 1));
    const int64_t e = next_edge_after(tb, t);
    failures += !(e > t && e - tb.bit_period_ns <= t && bit_start(tb, bit_number(tb, e)) == e);
    const uint32_t idx = static_cast<uint32_t>(rng() % L);
    const int64_t s = next_start_of_index(tb, t, idx, L);
    failures += !(s >= t && bit_index(tb, s, L) == idx && bit_start(tb, bit_number(tb, s)) == s &&
                  s - t < static_cast<int64_t>(L) * tb.bit_period_ns);
  }
  EXPECT_EQ(failures, 0);
}

}  // namespace
}  // namespace tetrapulse::protocol
