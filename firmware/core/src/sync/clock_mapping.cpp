#include "tetrapulse/fw/sync/clock_mapping.hpp"

#include "tetrapulse/fw/sync/fixed_point.hpp"

namespace tetrapulse::fw {
namespace {

constexpr uint64_t kNsPerSecond = 1'000'000'000;

// t - anchor as a signed count, saturated.
int64_t signed_diff(Tick t, Tick anchor) {
  if (t >= anchor) {
    const uint64_t d = t - anchor;
    return d > static_cast<uint64_t>(INT64_MAX) ? INT64_MAX : static_cast<int64_t>(d);
  }
  const uint64_t d = anchor - t;
  return d > static_cast<uint64_t>(INT64_MAX) ? -INT64_MAX : -static_cast<int64_t>(d);
}

int64_t saturating_add(int64_t a, int64_t b) {
  if (b > 0 && a > INT64_MAX - b) return INT64_MAX;
  if (b < 0 && a < INT64_MIN - b) return INT64_MIN;
  return a + b;
}

}  // namespace

ClockMapping::ClockMapping(uint32_t tick_hz) : tick_hz_(tick_hz == 0 ? 1 : tick_hz) {
  nominal_ns_per_tick_ = shl_div(kNsPerSecond, kNsPerTickShift, tick_hz_);
  update_rates();
}

void ClockMapping::update_rates() {
  const int64_t nominal = static_cast<int64_t>(nominal_ns_per_tick_ > static_cast<uint64_t>(INT64_MAX)
                                                   ? static_cast<uint64_t>(INT64_MAX)
                                                   : nominal_ns_per_tick_);
  const int64_t delta = mul_shr_signed(correction_, nominal_ns_per_tick_, kCorrectionShift);
  const int64_t rate = saturating_add(nominal, delta);
  ns_per_tick_ = rate > 0 ? static_cast<uint64_t>(rate) : 1;
  // ticks per ns (Q16.48) = 2^(48 + 40) / ns_per_tick (Q24.40)
  ticks_per_ns_ = shl_div(1, kTicksPerNsShift + kNsPerTickShift, ns_per_tick_);
}

int32_t correction_to_ppb(int64_t correction) {
  // |c| stays far below 2^33 (the servo clamps it to 500 ppm), so c * 1e9 fits.
  const int64_t c = clamp64(correction, -(int64_t{1} << 38), int64_t{1} << 38);
  const int64_t ppb = div_round(-c * static_cast<int64_t>(kNsPerSecond), (int64_t{1} << kCorrectionShift) + c);
  return static_cast<int32_t>(clamp64(ppb, INT32_MIN, INT32_MAX));
}

int32_t ClockMapping::rate_ppb() const { return correction_to_ppb(correction_); }

int64_t ClockMapping::to_rig(Tick t) const {
  return saturating_add(rig_anchor_, mul_shr_signed(signed_diff(t, tick_anchor_), ns_per_tick_, kNsPerTickShift));
}

Tick ClockMapping::to_local(int64_t rig_ns) const {
  int64_t dr;
  if (rig_ns >= 0 && rig_anchor_ < 0 && rig_ns > INT64_MAX + rig_anchor_) {
    dr = INT64_MAX;
  } else if (rig_ns < 0 && rig_anchor_ > 0 && rig_ns < INT64_MIN + rig_anchor_) {
    dr = -INT64_MAX;
  } else {
    dr = rig_ns - rig_anchor_;
  }
  const int64_t dt = mul_shr_signed(dr, ticks_per_ns_, kTicksPerNsShift);
  if (dt < 0) {
    const uint64_t back = static_cast<uint64_t>(-dt);
    return back > tick_anchor_ ? 0 : tick_anchor_ - back;
  }
  const uint64_t ahead = static_cast<uint64_t>(dt);
  return ahead > UINT64_MAX - tick_anchor_ ? UINT64_MAX : tick_anchor_ + ahead;
}

int64_t ClockMapping::span_ns(int64_t ticks, int64_t correction) const {
  const int64_t delta = mul_shr_signed(correction, nominal_ns_per_tick_, kCorrectionShift);
  const int64_t rate = saturating_add(static_cast<int64_t>(nominal_ns_per_tick_), delta);
  return mul_shr_signed(ticks, rate > 0 ? static_cast<uint64_t>(rate) : 1, kNsPerTickShift);
}

void ClockMapping::set_rate(Tick t, int64_t correction) {
  rig_anchor_ = to_rig(t);
  tick_anchor_ = t;
  correction_ = correction;
  update_rates();
}

void ClockMapping::step(Tick t, int64_t rig_ns) {
  tick_anchor_ = t;
  rig_anchor_ = rig_ns;
}

}  // namespace tetrapulse::fw
