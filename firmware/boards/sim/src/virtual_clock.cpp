#include "tetrapulse/sim_board/virtual_clock.hpp"

#include <cmath>

namespace tetrapulse::sim_board {

VirtualClock::VirtualClock(uint32_t tick_hz, double drift_ppm) : tick_hz_(tick_hz) {
  segments_.push_back(Segment{0, 0, drift_ppm});
}

long double VirtualClock::ticks_per_ns(double ppm) const {
  return static_cast<long double>(tick_hz_) * (1.0L + static_cast<long double>(ppm) * 1e-6L) / 1e9L;
}

void VirtualClock::restart(int64_t rig_ns) {
  const double ppm = drift_ppm();
  segments_.clear();
  segments_.push_back(Segment{rig_ns, 0, ppm});
}

void VirtualClock::set_drift(int64_t rig_ns, double drift_ppm) {
  const Segment& last = segments_.back();
  if (rig_ns < last.rig_start) rig_ns = last.rig_start;
  segments_.push_back(Segment{rig_ns, ticks_at(rig_ns), drift_ppm});
}

const VirtualClock::Segment& VirtualClock::segment_for_rig(int64_t rig_ns) const {
  for (size_t i = segments_.size(); i-- > 1;) {
    if (rig_ns >= segments_[i].rig_start) return segments_[i];
  }
  return segments_.front();
}

long double VirtualClock::ticks_at(int64_t rig_ns) const {
  const Segment& s = segment_for_rig(rig_ns);
  const long double t = s.tick_start + static_cast<long double>(rig_ns - s.rig_start) * ticks_per_ns(s.ppm);
  return t < 0 ? 0 : t;
}

fw::Tick VirtualClock::tick_at(int64_t rig_ns) const {
  return static_cast<fw::Tick>(std::floor(ticks_at(rig_ns)));
}

long double VirtualClock::rig_at_tick(fw::Tick tick) const {
  const long double t = static_cast<long double>(tick);
  for (size_t i = segments_.size(); i-- > 0;) {
    const Segment& s = segments_[i];
    if (t >= s.tick_start || i == 0) return static_cast<long double>(s.rig_start) + (t - s.tick_start) / ticks_per_ns(s.ppm);
  }
  return 0;
}

}  // namespace tetrapulse::sim_board
