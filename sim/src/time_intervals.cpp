#include "tetrapulse/sim/time_intervals.hpp"

#include <algorithm>

namespace tetrapulse::sim {

TimeIntervals::TimeIntervals(std::vector<TimeInterval> intervals) {
  std::sort(intervals.begin(), intervals.end(), [](const TimeInterval& a, const TimeInterval& b) {
    return a.begin_ns != b.begin_ns ? a.begin_ns < b.begin_ns : a.end_ns < b.end_ns;
  });
  for (const TimeInterval& iv : intervals) {
    if (iv.end_ns <= iv.begin_ns) continue;
    if (!intervals_.empty() && iv.begin_ns <= intervals_.back().end_ns) {
      intervals_.back().end_ns = std::max(intervals_.back().end_ns, iv.end_ns);
    } else {
      intervals_.push_back(iv);
    }
  }
}

const TimeInterval* TimeIntervals::find(int64_t t_ns) const {
  auto it = std::upper_bound(intervals_.begin(), intervals_.end(), t_ns,
                             [](int64_t t, const TimeInterval& iv) { return t < iv.begin_ns; });
  if (it == intervals_.begin()) return nullptr;
  --it;
  return t_ns < it->end_ns ? &*it : nullptr;
}

bool TimeIntervals::contains(int64_t t_ns) const { return find(t_ns) != nullptr; }

}  // namespace tetrapulse::sim
