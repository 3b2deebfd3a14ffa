#pragma once
// The Linux board's local clock: CLOCK_MONOTONIC in nanoseconds (tick_hz 1e9), optionally
// run off by a fixed rate error to stand in for a crystal (tests give the servo real work):
//
//   tick = monotonic_ns + (monotonic_ns - start_ns) * ppm 1e-6
//
// The clock servo of the firmware core disciplines it to rig time; the host's rig time is
// CLOCK_MONOTONIC + an offset (host/rig_clock.hpp), so on one machine the board's error
// against rig time can be measured directly (to_monotonic()).
#include <cstdint>

#include "tetrapulse/fw/clock/local_clock.hpp"

namespace tetrapulse::linux_board {

int64_t monotonic_ns();
// CLOCK_REALTIME now, in ns: the clock of SocketCAN's SO_TIMESTAMPNS receive stamps.
int64_t realtime_ns();

class MonotonicClock final : public fw::LocalClock {
 public:
  static constexpr uint32_t kTickHz = 1'000'000'000;

  // `ppm`: rate error of the ticks against CLOCK_MONOTONIC, |ppm| <= 1000.
  explicit MonotonicClock(double ppm = 0);

  fw::Tick at(int64_t monotonic) const;
  // The CLOCK_MONOTONIC time at which the counter reads `tick`.
  int64_t to_monotonic(fw::Tick tick) const;

 private:
  fw::Tick do_now() const override { return at(monotonic_ns()); }
  uint32_t do_tick_hz() const override { return kTickHz; }

  int64_t start_ns_;
  int64_t ppb_;
};

}  // namespace tetrapulse::linux_board
