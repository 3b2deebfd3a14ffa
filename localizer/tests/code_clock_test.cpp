// The contract's bit timing (docs/rig-dataset.md) and how codes explain a
// track's read bits: exposures inside one bit, across edges, free-running phases.
#include "tetrapulse/localizer/code_clock.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tetrapulse/localizer/code_match.hpp"

namespace tetrapulse {
namespace {

constexpr int64_t kBit = 10'000'000;

Code code(const char* text) { return *parse_code(text, nullptr); }

TEST(CodeClock, BitNumberIsTheContractsFloor) {
  const CodeClock c{1'000, kBit, 1.0};
  EXPECT_EQ(c.bit_number(1'000), 0);
  EXPECT_EQ(c.bit_number(1'000 + kBit - 1), 0);
  EXPECT_EQ(c.bit_number(1'000 + kBit), 1);
  EXPECT_EQ(c.bit_number(999), -1);  // before the epoch: floor, not truncation
  EXPECT_EQ(c.bit_number(1'000 - kBit), -1);
  EXPECT_EQ(c.bit_number(1'000 - kBit - 1), -2);
}

TEST(CodeClock, AFastBoardReachesItsBitsEarlier) {
  const CodeClock c{0, kBit, 1 + 200e-6};
  // Bit 5000 starts at 5000 T / rate rig ns.
  EXPECT_EQ(c.bit_number(int64_t(5000 * kBit / (1 + 200e-6)) + 10), 5000);
  EXPECT_EQ(c.bit_number(5000 * kBit - 10), 5000);  // a nominal clock would still be in bit 4999
}

TEST(ExpectedBit, ExposureInsideOneBitSeesIt) {
  const Code c = code("0110");
  const CodeClock clock{0, kBit, 1.0};
  EXPECT_EQ(expected_bit(clock, c, 4'000'000, 2'000'000), ExpectedBit::kZero);
  EXPECT_EQ(expected_bit(clock, c, kBit, kBit), ExpectedBit::kOne);  // exactly [edge, next edge)
  EXPECT_EQ(expected_bit(clock, c, 5 * kBit + 1, 2'000'000), ExpectedBit::kOne);  // bit 5 = index 1, cyclic
}

TEST(ExpectedBit, ExposureAcrossAnEdgeMixesOnlyDifferentBits) {
  const Code c = code("0110");
  const CodeClock clock{0, kBit, 1.0};
  EXPECT_EQ(expected_bit(clock, c, kBit - 1'000'000, 2'000'000), ExpectedBit::kMixed);       // 0 -> 1
  EXPECT_EQ(expected_bit(clock, c, 2 * kBit - 1'000'000, 2'000'000), ExpectedBit::kOne);     // 1 -> 1
  EXPECT_EQ(expected_bit(clock, c, 4 * kBit - 1'000'000, 2'000'000), ExpectedBit::kZero);    // 0 -> 0 (wraps)
  EXPECT_EQ(expected_bit(clock, c, 0, 5 * kBit), ExpectedBit::kMixed);                       // a whole cycle
}

// Against the definition: the bits of every bit number from the exposure's first
// nanosecond to its last (bit_number of each), for synchronized and drifting
// clocks, starts before and after the origin, exposures from none to several bits.
TEST(ExpectedBit, IsTheBitsOfEveryNanosecondsBitNumber) {
  const Code c = code("0110100111");
  const int64_t L = c.length;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int64_t> start(-50 * kBit, 50 * kBit), exposure(-5, 3 * kBit);
  int mixed = 0, clear = 0;
  for (const double rate : {1.0, 1 - 150e-6, 1 + 200e-6}) {
    const CodeClock clock{123'457, kBit, rate};
    for (int k = 0; k < 20000; ++k) {
      // Half of them end within a few nanoseconds of a nominal edge (the remainder
      // arithmetic's boundary cases), the others anywhere.
      const int64_t before_edge = (k / 2) % 4, edge = 123'457 + (start(rng) / kBit) * kBit;
      const int64_t t = k % 2 ? start(rng) : edge - before_edge;
      const int64_t e = k % 2 ? exposure(rng) : before_edge + (k / 8) % 3 - 1 + (k % 16 < 8 ? 0 : kBit);
      const int64_t first = clock.bit_number(t), last = clock.bit_number(t + std::max<int64_t>(e, 1) - 1);
      const auto bit = [&](int64_t n) { return c.bit(uint32_t(((n % L) + L) % L)); };
      bool both = false;
      for (int64_t n = first + 1; n <= last && n <= first + L; ++n) both |= bit(n) != bit(first);
      const ExpectedBit want = both ? ExpectedBit::kMixed : bit(first) ? ExpectedBit::kOne : ExpectedBit::kZero;
      ASSERT_EQ(expected_bit(clock, c, t, e), want) << "rate " << rate << " start " << t << " exposure " << e;
      (both ? mixed : clear) += 1;
    }
  }
  EXPECT_GT(mixed, 1000);
  EXPECT_GT(clear, 1000);
}

TEST(MeanEmission, FollowsTheModulation) {
  const Code c = code("10");
  const CodeClock clock{0, kBit, 1.0};
  Modulation on_off;
  Modulation two_level{ModulationKind::kTwoLevel, 0.3};
  Modulation constant{ModulationKind::kConstant, 0};
  EXPECT_DOUBLE_EQ(mean_emission(clock, on_off, c, 0, kBit), 1.0);
  EXPECT_DOUBLE_EQ(mean_emission(clock, on_off, c, kBit, kBit), 0.0);
  EXPECT_DOUBLE_EQ(mean_emission(clock, on_off, c, kBit / 2, kBit), 0.5);
  EXPECT_DOUBLE_EQ(mean_emission(clock, two_level, c, kBit / 2, kBit), 0.65);
  EXPECT_DOUBLE_EQ(mean_emission(clock, constant, c, kBit, kBit), 1.0);
  EXPECT_DOUBLE_EQ(mean_emission(clock, on_off, std::nullopt, kBit, kBit), 1.0);  // no code: constant
}

// A track's history and read bits made from a code under a clock: one sample per
// frame, 2 ms exposures, frames `frame_ns` apart starting at start_ns.
struct ReadTrack {
  RingBuffer<TrackSample, kTrackHistory> history;
  TrackBits bits{};
};

ReadTrack read_track(const Code& c, const CodeClock& clock, int64_t start_ns, int64_t frame_ns, int frames) {
  ReadTrack r;
  for (int k = 0; k < frames; ++k) {
    TrackSample s;
    s.frame = k;
    s.timestamp_ns = start_ns + k * frame_ns;
    s.exposure_ns = 2'000'000;
    s.measured = true;
    r.history.push(s);
  }
  for (size_t j = 0; j < r.history.size(); ++j) {
    const ExpectedBit e = expected_bit(clock, c, r.history[j].timestamp_ns, r.history[j].exposure_ns);
    r.bits[j] = e == ExpectedBit::kOne ? ReadBit::kOne : e == ExpectedBit::kZero ? ReadBit::kZero : ReadBit::kUnknown;
  }
  return r;
}

TEST(MatchCode, CountsMismatchesAgainstTheRightAndWrongCodes) {
  const Code truth = code("010011100101"), other = code("011001001001");
  const CodeClock clock{0, kBit, 1.0};
  ReadTrack r = read_track(truth, clock, 4'000'000, kBit, 24);
  EXPECT_EQ(match_code(r.history, r.bits, 0, clock, truth).mismatches, 0);
  EXPECT_EQ(match_code(r.history, r.bits, 0, clock, truth).counted, 24);
  // Two full cycles: twice the codes' Hamming distance.
  int distance = 0;
  for (uint32_t i = 0; i < 12; ++i) distance += truth.bit(i) != other.bit(i);
  EXPECT_EQ(match_code(r.history, r.bits, 0, clock, other).mismatches, 2 * distance);
  // A read error shows as one mismatch.
  r.bits[5] = r.bits[5] == ReadBit::kOne ? ReadBit::kZero : ReadBit::kOne;
  EXPECT_EQ(match_code(r.history, r.bits, 0, clock, truth).mismatches, 1);
  // Starting later leaves the early samples out.
  EXPECT_EQ(match_code(r.history, r.bits, 6, clock, truth).mismatches, 0);
}

TEST(MatchCodePhases, FindsAFreeRunningBoardsPhaseAndNoOtherCodeFits) {
  // A board whose bits start 3.7 code periods and 4.3 ms after rig time 0; phases
  // searched 8 per bit. The best phase explains every bit; a cyclic shift does not.
  const Code truth = code("111001110001011"), other = code("010110001100100");
  const CodeClock board{int64_t(3.7 * 15 * kBit) + 4'300'000, kBit, 1.0};
  const ReadTrack r = read_track(truth, board, 0, kBit, 45);
  std::vector<CodeMatch> phases;
  match_code_phases(r.history, r.bits, 0, 0, kBit, 8, truth, &phases);
  ASSERT_EQ(phases.size(), 15u * 8u);
  size_t best = 0;
  for (size_t g = 0; g < phases.size(); ++g)
    if (phases[g].cost() < phases[best].cost()) best = g;
  EXPECT_EQ(phases[best].cost(), 0);
  EXPECT_GE(phases[best].counted, 40);
  // The best phase's origin is the board's, modulo the code period, within the
  // freedom the samples leave (the 2 ms exposures sit inside the bits).
  const int64_t period = 15 * kBit;
  const int64_t offset = ((phase_origin(0, kBit, 8, int(best)) - board.origin_ns) % period + period) % period;
  EXPECT_TRUE(offset < 8'000'000 || offset > period - 8'000'000) << offset;
  std::vector<CodeMatch> wrong;
  match_code_phases(r.history, r.bits, 0, 0, kBit, 8, other, &wrong);
  for (const CodeMatch& m : wrong) EXPECT_GE(m.cost(), 3.0);
}

}  // namespace
}  // namespace tetrapulse
