#include "tetrapulse/linux_board/monotonic_clock.hpp"

#include <time.h>

#include <cmath>
#include <cstdint>

namespace tetrapulse::linux_board {

namespace {

int64_t read_clock(clockid_t id) {
  timespec t{};
  clock_gettime(id, &t);
  return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace

int64_t monotonic_ns() { return read_clock(CLOCK_MONOTONIC); }

int64_t realtime_ns() { return read_clock(CLOCK_REALTIME); }

MonotonicClock::MonotonicClock(double ppm)
    : start_ns_(monotonic_ns()), ppb_(static_cast<int64_t>(std::llround(ppm * 1000.0))) {}

fw::Tick MonotonicClock::at(int64_t monotonic) const {
  const int64_t since = monotonic - start_ns_;
  // since * ppb / 1e9, split into whole seconds and the rest so that it cannot overflow.
  const int64_t extra = (since / 1'000'000'000) * ppb_ + (since % 1'000'000'000) * ppb_ / 1'000'000'000;
  return static_cast<fw::Tick>(monotonic + extra);
}

int64_t MonotonicClock::to_monotonic(fw::Tick tick) const {
  // Invert at() by fixed-point iteration: the rate error is at most 1e-3, so each step
  // shrinks the error a thousandfold.
  int64_t m = static_cast<int64_t>(tick);
  for (int i = 0; i < 3; ++i) m += static_cast<int64_t>(tick) - static_cast<int64_t>(at(m));
  return m;
}

}  // namespace tetrapulse::linux_board
