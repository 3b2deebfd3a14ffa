// The clock offset from bracketed reads (clock_bracket.hpp), on scripted clocks: which
// bracket is taken, and the error bound over many preempted reads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "tetrapulse/protocol/clock_bracket.hpp"

namespace tetrapulse::protocol {
namespace {

// Reads that return a script, reference and other interleaved as bracketed_clock_offset_ns() asks.
struct ScriptedReads {
  std::vector<int64_t> reference;
  std::vector<int64_t> other;
  size_t next_reference = 0;
  size_t next_other = 0;

  int64_t offset() {
    return bracketed_clock_offset_ns([this] { return reference.at(next_reference++); },
                                     [this] { return other.at(next_other++); });
  }
};

TEST(ClockBracket, TakesTheTightestOfThreeBrackets) {
  // Spans 400, 20 and 90 ns: the second bracket's midpoint, 1'000'110, is 1'999'895 ns behind.
  ScriptedReads r{{1'000'000, 1'000'400, 1'000'100, 1'000'120, 1'000'200, 1'000'290}, {3'000'300, 3'000'005, 3'000'100}};
  EXPECT_EQ(r.offset(), 3'000'005 - 1'000'110);
  EXPECT_EQ(r.next_reference, 6u);
  EXPECT_EQ(r.next_other, 3u) << "exactly kClockBrackets brackets";
}

TEST(ClockBracket, TheFirstOfEqualBracketsWins) {
  ScriptedReads r{{0, 10, 100, 110, 200, 210}, {5, 107, 209}};
  EXPECT_EQ(r.offset(), 0);
}

TEST(ClockBracket, ErrorStaysWithinHalfTheTightestBracketWhateverThePreemptions) {
  // Two clocks offset by `truth`; each read takes 20..60 ns, and now and then a read is
  // preempted for up to 200 us (a loaded or emulated machine).
  std::mt19937_64 random(20240611);
  std::uniform_int_distribution<int64_t> read_ns(20, 60);
  std::uniform_int_distribution<int64_t> preempted_ns(1'000, 200'000);
  std::uniform_int_distribution<int64_t> offset_ns(-1'000'000'000'000, 1'000'000'000'000);
  std::bernoulli_distribution preempt(0.3);
  int outside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int64_t truth = offset_ns(random);
    int64_t now = 5'000'000'000 + trial;
    // A read returns the instant in the middle of its own duration; then time moves on.
    auto instant = [&] {
      const int64_t duration = read_ns(random);
      const int64_t at = now + duration / 2;
      now += duration + (preempt(random) ? preempted_ns(random) : 0);
      return at;
    };
    std::vector<int64_t> reference_reads;
    const int64_t got = bracketed_clock_offset_ns(
        [&] {
          reference_reads.push_back(instant());
          return reference_reads.back();
        },
        [&] { return instant() + truth; });
    ASSERT_EQ(reference_reads.size(), 2u * kClockBrackets);
    int64_t tightest = INT64_MAX;
    for (size_t i = 0; i < reference_reads.size(); i += 2) {
      tightest = std::min(tightest, reference_reads[i + 1] - reference_reads[i]);
    }
    if (std::llabs(got - truth) > tightest / 2 + 1) ++outside;  // +1: the midpoint is rounded down
  }
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace tetrapulse::protocol
