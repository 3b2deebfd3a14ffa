// The code player on a simulated board whose crystal is exact (so board time is rig
// time): levels follow SPEC.md §9 bit for bit, only level changes are scheduled, each at
// its bit edge; brightness, two_level, constant, current limit and Identify.
#include <gtest/gtest.h>

#include <cmath>

#include "board_testing.hpp"
#include "tetrapulse/fw/leds/led_program.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::Code;
using protocol::Config;
using protocol::Modulation;

// Expected duty of marker m at rig time t under `config` (the contract's formula).
double contract_level(const Config& c, size_t m, int64_t t, uint16_t ceiling = kDutyFull) {
  const Code& code = c.codes[m];
  const double one = std::min<double>(c.brightness, ceiling);
  if (c.modulation == Modulation::kConstant || code.length == 0) return one / kDutyFull;
  const protocol::TimeBase tb{c.epoch_ns, c.bit_period_ns};
  const bool bit = code.bit(protocol::bit_index(tb, t, code.length));
  if (bit) return one / kDutyFull;
  if (c.modulation == Modulation::kOnOff) return 0;
  return std::min<double>(std::round(c.brightness * static_cast<double>(c.low_level) / kDutyFull), ceiling) / kDutyFull;
}

sim_board::SimBoardOptions exact_board() {
  sim_board::SimBoardOptions o;
  o.clock_ppm = 0;
  o.power_on_ns = 0;
  o.tick_hz = 100'000'000;  // 10 ns ticks: bit edges fall exactly on ticks
  return o;
}

void expect_plays(const Config& c, uint16_t ceiling = kDutyFull) {
  TestBoard b(exact_board());
  b.configure(c);
  const int64_t start = b.board.now() + 5 * kMs;
  const int64_t period = c.bit_period_ns;
  const int64_t bits = 300;
  b.board.advance_to(start + (bits + 2) * period);
  const int64_t first_bit = protocol::bit_number(protocol::TimeBase{c.epoch_ns, period}, start) + 1;
  size_t mismatches = 0;
  for (uint8_t m = 0; m < kLedCount; ++m) {
    for (int64_t n = first_bit; n < first_bit + bits; ++n) {
      const int64_t mid = c.epoch_ns + n * period + period / 2;
      const double got = b.board.leds().mean_duty(m, mid, mid + 1);
      if (std::fabs(got - contract_level(c, m, mid, ceiling)) > 1e-9) ++mismatches;
      // The whole bit at one level: the change happened at the edge, not inside the bit.
      const double whole = b.board.leds().mean_duty(m, c.epoch_ns + n * period, c.epoch_ns + (n + 1) * period);
      if (std::fabs(whole - got) > 1e-9) ++mismatches;
    }
    // Only level changes: consecutive applied changes of one marker differ.
    const auto& log = b.board.leds().log(m);
    for (size_t i = 1; i < log.size(); ++i) {
      if (log[i].rig_ns > start) {
        EXPECT_NE(log[i].duty, log[i - 1].duty) << "marker " << int{m};
      }
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(b.board.firmware()->board().player().late_changes(), 0u);
}

TEST(CodePlayer, PlaysTheContractFormulaOnOff) { expect_plays(edge_rich_config(kMs, 123'000)); }

TEST(CodePlayer, PlaysTwoLevelWithBrightness) {
  Config c = edge_rich_config(2 * kMs, -7 * kMs);
  c.modulation = Modulation::kTwoLevel;
  c.brightness = 40000;
  c.low_level = 20000;
  expect_plays(c);
}

TEST(CodePlayer, ConstantModulationAndCodelessMarkersStayLit) {
  Config c = edge_rich_config(kMs);
  c.codes[2] = Code{};
  expect_plays(c);
  c.modulation = Modulation::kConstant;
  expect_plays(c);
}

TEST(CodePlayer, LongCodesAndShortestBitPeriod) {
  Config c = edge_rich_config(protocol::kMinBitPeriodNs);
  c.codes[3] = Code{64, 0x1ff803fc07e0f1cdull};
  c.codes[2] = Code{63, 0x5555555555555555ull >> 1};
  expect_plays(c);
}

TEST(CodePlayer, DutyCappedByCurrentLimit) {
  Config c = edge_rich_config(kMs);
  c.current_limit_ma = 350;  // of the sim board's 1000 mA full scale
  c.modulation = Modulation::kTwoLevel;
  c.low_level = 60000;
  expect_plays(c, duty_ceiling(350, 1000));
  EXPECT_EQ(duty_ceiling(350, 1000), 22937);
  EXPECT_EQ(duty_ceiling(0, 1000), kDutyFull);
  EXPECT_EQ(duty_ceiling(2000, 1000), kDutyFull);
}

TEST(CodePlayer, IdentifyOverridesCodesForItsDurationThenCodesReturn) {
  TestBoard b(exact_board());
  Config c = edge_rich_config(kMs);
  b.configure(c);
  b.board.advance_to(100 * kMs);
  const int64_t start = b.board.now();
  b.request(protocol::Identify{protocol::IdentifyPattern::kBlinkAll, 1000});
  EXPECT_TRUE(b.board.firmware()->board().player().identifying());
  b.board.advance_to(start + 1500 * kMs);
  // Blink all: 250 ms on, 250 ms off, all markers together, from the Identify on.
  for (uint8_t m = 0; m < kLedCount; ++m) {
    EXPECT_NEAR(b.board.leds().mean_duty(m, start + 10 * kMs, start + 240 * kMs), 1.0, 1e-3);
    EXPECT_NEAR(b.board.leds().mean_duty(m, start + 260 * kMs, start + 490 * kMs), 0.0, 1e-3);
    EXPECT_NEAR(b.board.leds().mean_duty(m, start + 510 * kMs, start + 740 * kMs), 1.0, 1e-3);
  }
  EXPECT_FALSE(b.board.firmware()->board().player().identifying());
  // Codes again after the duration.
  for (int64_t n = 1100; n < 1400; ++n) {
    const int64_t mid = n * kMs + kMs / 2;
    for (uint8_t m = 0; m < kLedCount; ++m) {
      ASSERT_NEAR(b.board.leds().mean_duty(m, mid, mid + 1), contract_level(c, m, mid), 1e-9) << "bit " << n;
    }
  }
  // Chase until stopped.
  b.request(protocol::Identify{protocol::IdentifyPattern::kChase, 0});
  const int64_t chase = b.board.now();
  b.board.advance_to(chase + 3 * kSecond);
  EXPECT_TRUE(b.board.firmware()->board().player().identifying());
  for (uint8_t m = 0; m < kLedCount; ++m) {
    const int64_t on = chase + m * 200 * kMs;
    EXPECT_NEAR(b.board.leds().mean_duty(m, on + kMs, on + 199 * kMs), 1.0, 1e-3) << int{m};
    EXPECT_NEAR(b.board.leds().mean_duty(m, on + 201 * kMs, on + 799 * kMs), 0.0, 1e-3) << int{m};
  }
  b.request(protocol::Identify{protocol::IdentifyPattern::kStop, 0});
  EXPECT_FALSE(b.board.firmware()->board().player().identifying());
}

TEST(LedProgram, CountPatternBlinksMarkerIndexPlusOneTimes) {
  const LedProgram p = identify_program(protocol::IdentifyPattern::kCountIndex, 0, 1000);
  for (size_t m = 0; m < 4; ++m) {
    int blinks = 0;
    for (int64_t n = 0; n < 12; ++n) {
      if (p.duty(m, n) != 0 && (n == 0 || p.duty(m, n - 1) == 0)) ++blinks;
      EXPECT_LE(p.duty(m, n), 1000);
    }
    EXPECT_EQ(blinks, static_cast<int>(m) + 1);
  }
}

}  // namespace
}  // namespace tetrapulse::fw::testing
