#include "tetrapulse/sim/board_clock.hpp"

#include <cmath>

namespace tetrapulse::sim {

double BoardClock::board_time(double t_ns) const {
  const double rate = 1.0 + spec_.drift_ppm * 1e-6;
  const double offset = static_cast<double>(spec_.offset_ns);
  if (spec_.free_running) return offset + t_ns * rate;
  // A query inside a sync-loss interval: the board drifts from where it was at its start.
  const TimeInterval* lost = spec_.sync_loss.find(static_cast<int64_t>(std::floor(t_ns)));
  if (lost == nullptr) return t_ns + offset;
  const double s0 = static_cast<double>(lost->begin_ns);
  return s0 + offset + (t_ns - s0) * rate;
}

}  // namespace tetrapulse::sim
