#include "tetrapulse/sim/board_clock.hpp"

#include <cmath>

#include "tetrapulse/sim/scenario.hpp"

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

std::map<int, CodeClock> free_running_code_clocks(const Scenario& scenario) {
  std::map<int, CodeClock> out;
  const Timebase& timebase = scenario.targets.timebase;
  for (size_t t = 0; t < scenario.simulation.size() && t < scenario.targets.targets.size(); ++t) {
    const BoardClockSpec& c = scenario.simulation[t].clock;
    if (!c.free_running) continue;
    const double rate = 1.0 + c.drift_ppm * 1e-6;
    const double origin = double(timebase.epoch_ns - c.offset_ns) / rate;
    out[scenario.targets.targets[t].id] = CodeClock{int64_t(std::llround(origin)), timebase.bit_period_ns, rate};
  }
  return out;
}

}  // namespace tetrapulse::sim
