// Frequency codes (protocol/SPEC.md §8.5) from the code table: "111000" on marker 0 and
// "10" on marker 1, different lengths on one time base, on a simulated board. Every LED
// change falls exactly on the bit edge where the code's level changes, synchronised
// (crystal exact: board time is rig time) and free-running (crystal 150 ppm fast: the
// same edges, every one of them 150 ppm early against the rig's, none missing).
#include <gtest/gtest.h>

#include <cmath>

#include "board_testing.hpp"
#include "tetrapulse/fw/leds/led_program.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::Code;
using protocol::Config;

constexpr int64_t kBit = kMs;  // 1 ms bits: "111000" is 166.7 Hz, "10" 500 Hz

Config frequency_config() {
  Config c = protocol::default_config();
  c.bit_period_ns = kBit;
  c.epoch_ns = 0;
  c.codes[0] = Code{6, 0b000111};  // "111000"
  c.codes[1] = Code{2, 0b01};      // "10"
  c.codes[2] = Code{};             // constant
  c.codes[3] = Code{};
  return c;
}

sim_board::SimBoardOptions board_options(double ppm) {
  sim_board::SimBoardOptions o;
  o.clock_ppm = ppm;
  o.power_on_ns = 0;
  o.tick_hz = 100'000'000;  // 10 ns ticks: 1 ms edges fall on ticks
  return o;
}

// Bit numbers (board time = rate x rig time) of marker m's level changes in [from, to).
struct Edges {
  std::vector<int64_t> bits;  // nearest bit number of each change
  double worst_ns = 0;        // largest |change - that bit's edge| in board ns
};

Edges edges(const TestBoard& b, uint8_t m, int64_t from, int64_t to, double rate) {
  Edges e;
  for (long double t : change_times(b.board, m, from, to)) {
    const long double board_ns = t * rate;
    const auto n = static_cast<int64_t>(std::llround(static_cast<double>(board_ns / kBit)));
    e.bits.push_back(n);
    e.worst_ns = std::max(e.worst_ns, std::fabs(static_cast<double>(board_ns - static_cast<long double>(n) * kBit)));
  }
  return e;
}

// Marker 0 changes at every bit n = 0 or 3 (mod 6), marker 1 at every bit, nowhere else.
void expect_square_wave_edges(const TestBoard& b, int64_t from, int64_t to, double rate, double tolerance_ns) {
  const Edges six = edges(b, 0, from, to, rate);
  const Edges two = edges(b, 1, from, to, rate);
  ASSERT_GT(six.bits.size(), 100u);
  for (size_t i = 1; i < six.bits.size(); ++i) EXPECT_EQ(six.bits[i] - six.bits[i - 1], 3) << i;
  for (size_t i = 1; i < two.bits.size(); ++i) EXPECT_EQ(two.bits[i] - two.bits[i - 1], 1) << i;
  for (int64_t n : six.bits) EXPECT_EQ(n % 3, 0);
  EXPECT_LE(six.worst_ns, tolerance_ns);
  EXPECT_LE(two.worst_ns, tolerance_ns);
  // Three edges of "10" per edge of "111000": none skipped.
  EXPECT_NEAR(static_cast<double>(two.bits.size()), 3.0 * static_cast<double>(six.bits.size()), 3.0);
  // Levels: "111000" lit in bits 0..2 of its period, "10" in even bits.
  for (int64_t n = six.bits.front() + 1; n < six.bits.back() - 1; ++n) {
    const long double mid = (static_cast<long double>(n) * kBit + kBit / 2) / rate;
    const bool six_lit = ((n % 6) + 6) % 6 < 3;
    const bool two_lit = n % 2 == 0;
    ASSERT_NEAR(b.board.leds().mean_duty(0, mid, mid + 1), six_lit ? 1.0 : 0.0, 1e-9) << n;
    ASSERT_NEAR(b.board.leds().mean_duty(1, mid, mid + 1), two_lit ? 1.0 : 0.0, 1e-9) << n;
  }
}

TEST(FrequencyCodePlayer, SquareWavesOfDifferentLengthsChangeExactlyAtTheirEdges) {
  TestBoard b(board_options(0));
  b.configure(frequency_config());
  const int64_t from = b.board.now() + 5 * kMs;
  b.board.advance_to(from + 600 * kMs);
  expect_square_wave_edges(b, from, from + 590 * kMs, 1.0, 0.0);  // exact
  EXPECT_EQ(b.board.firmware()->board().player().late_changes(), 0u);
}

TEST(FrequencyCodePlayer, FreeRunningPlaysTheSameEdgesOnItsOwnCrystal) {
  const double ppm = 150;
  TestBoard b(board_options(ppm));
  b.configure(frequency_config());
  const int64_t from = b.board.now() + 5 * kMs;
  b.board.advance_to(from + 600 * kMs);
  // In board time the edges are exact to a tick (10 ns of a crystal running 150 ppm fast).
  expect_square_wave_edges(b, from, from + 590 * kMs, 1 + ppm * 1e-6, 10.0);
  EXPECT_EQ(b.board.firmware()->board().player().late_changes(), 0u);
}

}  // namespace
}  // namespace tetrapulse::fw::testing
