#pragma once
// The board's estimate of rig time as a function of its local counter, piecewise
// linear and continuous:
//
//   rig(tick) = rig_anchor + (tick - tick_anchor) * ns_per_tick
//   ns_per_tick = (1e9 / tick_hz) * (1 + correction),  correction in units of 2^-40
//
// Rates are fixed point (ns_per_tick Q24.40, ticks_per_ns Q16.48), so a mapping
// anchored an hour ago still converts to within a nanosecond. Rig times are integer ns.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"

namespace tetrapulse::fw {

constexpr unsigned kCorrectionShift = 40;  // correction is a fraction in units of 2^-40
constexpr unsigned kNsPerTickShift = 40;
constexpr unsigned kTicksPerNsShift = 48;

// The local counter's rate error in ppb for a rate correction c (2^-40 units): the
// counter runs at (1 + r) of nominal with (1 + c)(1 + r) = 1, so r = -c / (1 + c).
int32_t correction_to_ppb(int64_t correction);

class ClockMapping {
 public:
  ClockMapping() = default;
  // Identity-rate mapping of a `tick_hz` counter: rig(0) = 0, no correction.
  explicit ClockMapping(uint32_t tick_hz);

  uint32_t tick_hz() const { return tick_hz_; }
  Tick tick_anchor() const { return tick_anchor_; }
  int64_t rig_anchor() const { return rig_anchor_; }
  // Rate correction (fraction, 2^-40 units): positive when the local counter runs slow.
  int64_t correction() const { return correction_; }
  // Local clock rate error in parts per billion (positive: the counter runs fast).
  int32_t rate_ppb() const;

  // Rig time (ns) at local tick `t` (any t, before or after the anchor).
  int64_t to_rig(Tick t) const;
  // The local tick at which rig time reaches `rig_ns` (rounded to the nearest tick; 0 if
  // that is before the counter started).
  Tick to_local(int64_t rig_ns) const;

  // Rig ns spanned by `ticks` local ticks at rate correction `correction` (any sign).
  int64_t span_ns(int64_t ticks, int64_t correction) const;

  // Moves the anchor to `t` keeping rig(t) (continuous), then applies `correction`.
  void set_rate(Tick t, int64_t correction);
  // Makes rig(t) = rig_ns (a step), keeping the rate.
  void step(Tick t, int64_t rig_ns);

 private:
  void update_rates();

  uint32_t tick_hz_ = 1;
  Tick tick_anchor_ = 0;
  int64_t rig_anchor_ = 0;
  int64_t correction_ = 0;
  uint64_t nominal_ns_per_tick_ = 0;  // Q24.40
  uint64_t ns_per_tick_ = 0;          // Q24.40
  uint64_t ticks_per_ns_ = 0;         // Q16.48
};

}  // namespace tetrapulse::fw
