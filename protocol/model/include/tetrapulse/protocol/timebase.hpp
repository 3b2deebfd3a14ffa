#pragma once
// Rig time-base arithmetic in integer nanoseconds (no floating point).
//
// Bit n of every code occupies rig times  [epoch + n*T, epoch + (n+1)*T),
// n in Z (negative before the epoch); a code of length L plays bit n mod L.
// (docs/rig-dataset.md: bit index = floor((t - epoch) / T) mod L.)
// Domain: T > 0 and |t - epoch| < 2^62 ns (about 146 years).
#include <cstdint>

namespace tetrapulse::protocol {

// The one time base of codes (the boards', the localizer's, the simulator's and
// targets.yaml's `timebase`).
struct TimeBase {
  int64_t epoch_ns = 0;                // rig time at which bit 0 starts
  int64_t bit_period_ns = 10'000'000;  // T, length of one bit, > 0
  // Whether the boards are disciplined to rig time (GPIO or CAN sync). When false
  // they run free: epoch and rate are each board's own, found by the localizer.
  bool synchronized = true;

  constexpr bool valid() const { return bit_period_ns > 0; }
};

// floor(a / b) for b > 0.
constexpr int64_t floor_div(int64_t a, int64_t b) {
  const int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// a mod b in [0, b) for b > 0.
constexpr int64_t floor_mod(int64_t a, int64_t b) {
  const int64_t r = a % b;
  return r < 0 ? r + b : r;
}

// n such that epoch + n*T <= t < epoch + (n+1)*T.
constexpr int64_t bit_number(const TimeBase& tb, int64_t t_ns) {
  return floor_div(t_ns - tb.epoch_ns, tb.bit_period_ns);
}

// Index into a code of length L (> 0) played cyclically: bit_number mod L.
constexpr uint32_t bit_index(const TimeBase& tb, int64_t t_ns, uint32_t code_length) {
  return static_cast<uint32_t>(floor_mod(bit_number(tb, t_ns), static_cast<int64_t>(code_length)));
}

// Rig time at which bit n starts: epoch + n*T (inverse of bit_number).
constexpr int64_t bit_start(const TimeBase& tb, int64_t n) { return tb.epoch_ns + n * tb.bit_period_ns; }

// The first bit edge strictly after t.
constexpr int64_t next_edge_after(const TimeBase& tb, int64_t t_ns) {
  return bit_start(tb, bit_number(tb, t_ns) + 1);
}

// The first time >= t at which a bit with index `index` (< L) of a code of length L starts
// (inverse of bit_index).
constexpr int64_t next_start_of_index(const TimeBase& tb, int64_t t_ns, uint32_t index,
                                      uint32_t code_length) {
  const int64_t L = code_length;
  int64_t n = bit_number(tb, t_ns);
  if (bit_start(tb, n) < t_ns) ++n;  // first bit starting at or after t
  const int64_t k = floor_mod(static_cast<int64_t>(index) - n, L);
  return bit_start(tb, n + k);
}

// True when the window [start, start + duration) touches more than one bit,
// so a camera exposure over it mixes two bit levels. duration > 0.
constexpr bool straddles_edge(const TimeBase& tb, int64_t start_ns, int64_t duration_ns) {
  return bit_number(tb, start_ns) != bit_number(tb, start_ns + duration_ns - 1);
}

}  // namespace tetrapulse::protocol
