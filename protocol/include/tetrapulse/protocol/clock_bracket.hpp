#pragma once
// The offset between two clocks of one machine (integer ns), from reads of one clock
// bracketed by reads of the other. With  before = R(t0), other = O(t1), after = R(t2),
// t0 <= t1 <= t2, and O = R + offset:
//
//   offset = other - (before + (after - before) / 2),   |error| <= (after - before) / 2
//
// A preemption inside a bracket (a loaded or emulated machine) only widens it, so the
// tightest of kClockBrackets brackets is taken (the first of equal ones). The host
// (host/rig_clock.hpp) and the Linux board (its SocketCAN receive stamps) put CLOCK_REALTIME
// kernel timestamps on CLOCK_MONOTONIC through this; the clock reads are theirs: this is
// only the arithmetic, freestanding like the rest of the protocol.
#include <cstdint>

namespace tetrapulse::protocol {

constexpr int kClockBrackets = 3;

// O - R from kClockBrackets brackets; `reference` and `other` return R and O now (ns).
template <typename ReadReference, typename ReadOther>
int64_t bracketed_clock_offset_ns(ReadReference&& reference, ReadOther&& other) {
  int64_t best_span = INT64_MAX;
  int64_t offset = 0;
  for (int i = 0; i < kClockBrackets; ++i) {
    const int64_t before = reference();
    const int64_t between = other();
    const int64_t after = reference();
    if (after - before < best_span) {
      best_span = after - before;
      offset = between - (before + (after - before) / 2);
    }
  }
  return offset;
}

}  // namespace tetrapulse::protocol
