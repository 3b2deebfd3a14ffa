#include "tetrapulse/host/rig_clock.hpp"

#include <time.h>

#include <cstdint>

#include "tetrapulse/protocol/clock_bracket.hpp"

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
  return protocol::bracketed_clock_offset_ns(monotonic_now_ns, realtime_now_ns);
}

int64_t monotonic_from_realtime_ns(int64_t realtime_ns) { return realtime_ns - realtime_minus_monotonic_ns(); }

RigClock RigClock::starting_at(int64_t rig_now_ns) { return RigClock(rig_now_ns - monotonic_now_ns()); }

}  // namespace tetrapulse::host
