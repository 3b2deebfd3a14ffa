// Fixed-point clock arithmetic against long double references, over the whole range a
// board meets (tick rates 1 kHz..1 GHz, corrections +-1000 ppm, hours from the anchor).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "tetrapulse/fw/sync/clock_mapping.hpp"
#include "tetrapulse/fw/sync/fixed_point.hpp"

namespace tetrapulse::fw {
namespace {

// The host's 128-bit integers as the reference (the firmware has none).
__extension__ typedef __int128 I128;
__extension__ typedef unsigned __int128 U128Ref;

RC_GTEST_PROP(FixedPoint, MulShrMatchesWideArithmetic, ()) {
  const int64_t a = *rc::gen::inRange<int64_t>(-(int64_t{1} << 50), int64_t{1} << 50);
  const uint64_t b = *rc::gen::inRange<uint64_t>(0, uint64_t{1} << 50);
  const unsigned shift = *rc::gen::inRange<unsigned>(0, 63);
  const I128 exact = static_cast<I128>(a) * static_cast<I128>(b);
  const long double want = std::round(static_cast<long double>(exact) / std::ldexp(1.0L, static_cast<int>(shift)));
  if (std::fabs(want) < 9e18L) {
    RC_ASSERT(std::fabs(static_cast<long double>(mul_shr_signed(a, b, shift)) - want) <= 1.0L);
  }
}

RC_GTEST_PROP(FixedPoint, ShlDivMatchesWideArithmetic, ()) {
  const uint64_t a = *rc::gen::inRange<uint64_t>(0, uint64_t{1} << 40);
  const unsigned shift = *rc::gen::inRange<unsigned>(0, 60);
  const uint64_t d = *rc::gen::inRange<uint64_t>(1, uint64_t{1} << 62);
  const U128Ref exact = (static_cast<U128Ref>(a) << shift) / d;
  const uint64_t want = exact > UINT64_MAX ? UINT64_MAX : static_cast<uint64_t>(exact);
  RC_ASSERT(shl_div(a, shift, d) == want);
}

RC_GTEST_PROP(ClockMapping, ToRigAndToLocalAgreeWithExactRates, ()) {
  const uint32_t hz = *rc::gen::element<uint32_t>(1'000u, 32'768u, 1'000'000u, 84'000'000u, 168'000'000u, 1'000'000'000u);
  const int64_t ppm_x1000 = *rc::gen::inRange<int64_t>(-1'000'000, 1'000'000);
  const int64_t correction = static_cast<int64_t>(std::llround(static_cast<long double>(ppm_x1000) * 1e-9L * std::ldexp(1.0L, 40)));
  const Tick anchor = *rc::gen::inRange<Tick>(0, Tick{1} << 44);
  const int64_t rig_anchor = *rc::gen::inRange<int64_t>(-(int64_t{1} << 60), int64_t{1} << 60);
  const int64_t dt_s = *rc::gen::inRange<int64_t>(-3600, 3600);
  ClockMapping m(hz);
  m.step(anchor, rig_anchor);
  m.set_rate(anchor, correction);
  const long double ns_per_tick = 1e9L / hz * (1.0L + std::ldexp(static_cast<long double>(correction), -40));
  const int64_t dticks = dt_s * static_cast<int64_t>(hz);
  if (dticks < 0 && static_cast<Tick>(-dticks) > anchor) return;
  const Tick t = anchor + static_cast<Tick>(dticks);
  const long double want = static_cast<long double>(rig_anchor) + static_cast<long double>(dticks) * ns_per_tick;
  RC_ASSERT(std::fabs(static_cast<long double>(m.to_rig(t)) - want) <= 2.0L);
  // to_local inverts to_rig to within one tick.
  const Tick back = m.to_local(m.to_rig(t));
  RC_ASSERT((back > t ? back - t : t - back) <= 1u);
}

TEST(ClockMapping, RateReportFollowsCorrection) {
  ClockMapping m(84'000'000);
  const int64_t c = -static_cast<int64_t>(std::llround(100e-6 * std::ldexp(1.0, 40)));  // counter 100 ppm fast
  m.set_rate(0, c);
  EXPECT_NEAR(m.rate_ppb(), 100'010, 2);  // 1/(1 - 1e-4) - 1
}

}  // namespace
}  // namespace tetrapulse::fw
