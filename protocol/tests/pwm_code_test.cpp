// Bench PWM as a frequency code: exact cases, and the quantisation pwm_code.hpp states
// for any frequency and duty.
#include "tetrapulse/protocol/pwm_code.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "tetrapulse/protocol/code.hpp"  // is_square_wave

namespace tetrapulse::protocol {
namespace {

TEST(PwmCode, ExactCasesUseTheFewestBits) {
  const Result<PwmCode> half = pwm_code(1'000'000, 32768);  // 1 kHz, 50 %
  ASSERT_TRUE(half.ok());
  EXPECT_EQ(half->code.length, 2);
  EXPECT_EQ(half->code.bits, 0b01u);  // "10"
  EXPECT_EQ(half->bit_period_ns, 500'000u);
  EXPECT_EQ(half->frequency_millihertz, 1'000'000u);
  EXPECT_EQ(half->duty_q16, 32768u);
  const Result<PwmCode> quarter = pwm_code(100'000, 16384);  // 100 Hz, 25 %
  ASSERT_TRUE(quarter.ok());
  EXPECT_EQ(quarter->code.length, 4);
  EXPECT_EQ(quarter->code.bits, 0b0001u);  // "1000"
  EXPECT_EQ(quarter->bit_period_ns, 2'500'000u);
  const Result<PwmCode> thirty = pwm_code(1'000'000, 19661);  // 1 kHz, 30 %
  ASSERT_TRUE(thirty.ok());
  EXPECT_EQ(thirty->code.length, 10);
  EXPECT_EQ(thirty->code.bits, 0b111u);
  EXPECT_EQ(thirty->bit_period_ns, 100'000u);
}

TEST(PwmCode, RefusesWhatNoCodeCanPlay) {
  EXPECT_FALSE(pwm_code(60'000'000, 32768).ok());  // 60 kHz: a 2-bit period under 20 us
  EXPECT_FALSE(pwm_code(5, 32768).ok());
  EXPECT_FALSE(pwm_code(1'000'000, 0).ok());
  EXPECT_FALSE(pwm_code(1'000'000, 65536).ok());
}

RC_GTEST_PROP(PwmCode, QuantisationIsAsStated, ()) {
  const uint64_t mhz = *rc::gen::inRange<uint64_t>(1'000, 50'000'001);  // 1 Hz .. 50 kHz
  const uint32_t duty = *rc::gen::inRange<uint32_t>(1, 65536);
  const Result<PwmCode> p = pwm_code(mhz, duty);
  RC_ASSERT(p.ok());
  SquareWave wave;
  RC_ASSERT(is_square_wave(p->code, &wave));
  RC_ASSERT(p->bit_period_ns >= kMinBitPeriodNs);
  const double L = p->code.length;
  const double period_ns = L * p->bit_period_ns;
  const double wanted_ns = 1e12 / static_cast<double>(mhz);
  RC_ASSERT(std::fabs(period_ns - wanted_ns) <= 0.5 * L + 1e-6);
  // The duty is the nearest multiple of 1/L (within 1..L-1), and L is as fine as the
  // shortest bit period allows: 1/64, or the most bits of 10 us that fit the period.
  const double D = duty / 65536.0;
  const double finest = std::min(64.0, std::floor(wanted_ns / kMinBitPeriodNs));
  const double nearest_possible = std::fabs(std::round(std::clamp(D * finest, 1.0, finest - 1)) / finest - D);
  RC_ASSERT(std::fabs(wave.ones / L - D) <= nearest_possible + 1e-12);
  RC_ASSERT(std::fabs(p->frequency_millihertz - 1e12 / period_ns) <= 1.0);
}

}  // namespace
}  // namespace tetrapulse::protocol
