#include "tetrapulse/host/rig_clock.hpp"

#include <time.h>

#include <cstdint>

namespace tetrapulse::host {
namespace {

int64_t read_clock(clockid_t id) {
  timespec t{};
  clock_gettime(id, &t);
  return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace

int64_t monotonic_now_ns() { return read_clock(CLOCK_MONOTONIC); }
int64_t realtime_now_ns() { return read_clock(CLOCK_REALTIME); }

int64_t realtime_minus_monotonic_ns() {
  // The tightest of a few brackets: a preemption inside one (a loaded or emulated host)
  // would skew the difference by half its length.
  int64_t best_span = INT64_MAX, difference = 0;
  for (int i = 0; i < 3; ++i) {
    const int64_t before = read_clock(CLOCK_MONOTONIC);
    const int64_t real = read_clock(CLOCK_REALTIME);
    const int64_t after = read_clock(CLOCK_MONOTONIC);
    if (after - before < best_span) {
      best_span = after - before;
      difference = real - (before + (after - before) / 2);
    }
  }
  return difference;
}

int64_t monotonic_from_realtime_ns(int64_t realtime_ns) { return realtime_ns - realtime_minus_monotonic_ns(); }

RigClock RigClock::starting_at(int64_t rig_now_ns) { return RigClock(rig_now_ns - monotonic_now_ns()); }

}  // namespace tetrapulse::host
