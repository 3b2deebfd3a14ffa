#pragma once
// A simulated board's crystal: its local counter as a function of true rig time t (ns).
// The counter starts at 0 when the board powers up (or resets) and runs at
// tick_hz * (1 + drift_ppm 1e-6); the drift may change over time (temperature).
//
//   ticks(t) = tick_at_segment_start + (t - segment_start) * tick_hz * (1 + ppm 1e-6) / 1e9
#include <cstdint>
#include <vector>

#include "tetrapulse/fw/clock/tick.hpp"

namespace tetrapulse::sim_board {

class VirtualClock {
 public:
  VirtualClock(uint32_t tick_hz, double drift_ppm);

  uint32_t tick_hz() const { return tick_hz_; }
  double drift_ppm() const { return segments_.back().ppm; }

  // The counter restarts at 0 at rig time `rig_ns` (power-up, reset).
  void restart(int64_t rig_ns);
  // From rig time `rig_ns` on (not before the last change), the crystal runs at `drift_ppm`.
  void set_drift(int64_t rig_ns, double drift_ppm);

  // The counter's exact (fractional) value at rig time t; the counter reads its floor.
  long double ticks_at(int64_t rig_ns) const;
  fw::Tick tick_at(int64_t rig_ns) const;
  // The rig time (ns, fractional) at which the counter reaches `tick`.
  long double rig_at_tick(fw::Tick tick) const;

 private:
  struct Segment {
    int64_t rig_start = 0;
    long double tick_start = 0;
    double ppm = 0;
  };
  const Segment& segment_for_rig(int64_t rig_ns) const;
  long double ticks_per_ns(double ppm) const;

  uint32_t tick_hz_;
  std::vector<Segment> segments_;
};

}  // namespace tetrapulse::sim_board
