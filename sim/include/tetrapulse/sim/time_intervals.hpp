#pragma once
// A set of half-open rig-time intervals [begin_ns, end_ns) (integer nanoseconds of
// rig time): when a marker is occluded, when a board has lost sync.
#include <cstdint>
#include <vector>

namespace tetrapulse::sim {

struct TimeInterval {
  int64_t begin_ns = 0;
  int64_t end_ns = 0;  // > begin_ns
};

class TimeIntervals {
 public:
  TimeIntervals() = default;
  // Sorts and merges overlapping or touching intervals; empty ones are dropped.
  explicit TimeIntervals(std::vector<TimeInterval> intervals);

  const std::vector<TimeInterval>& intervals() const { return intervals_; }
  bool empty() const { return intervals_.empty(); }
  bool contains(int64_t t_ns) const;
  // The interval containing t, or nullptr.
  const TimeInterval* find(int64_t t_ns) const;

  // Calls fn(a, b, inside) for consecutive pieces [a, b) covering [t0, t1) (t0 < t1),
  // inside telling whether the piece lies in the set.
  template <typename Fn>
  void split(int64_t t0, int64_t t1, Fn&& fn) const {
    int64_t t = t0;
    for (const TimeInterval& iv : intervals_) {
      if (iv.end_ns <= t) continue;
      if (iv.begin_ns >= t1) break;
      if (iv.begin_ns > t) {
        fn(t, iv.begin_ns, false);
        t = iv.begin_ns;
      }
      const int64_t end = iv.end_ns < t1 ? iv.end_ns : t1;
      fn(t, end, true);
      t = end;
    }
    if (t < t1) fn(t, t1, false);
  }

 private:
  std::vector<TimeInterval> intervals_;
};

}  // namespace tetrapulse::sim
