// Rig time to CLOCK_REALTIME and back (ROS 2 stamps of live poses).
#include "tetrapulse/host/rig_clock.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace tetrapulse::host {
namespace {

TEST(RigClock, ToRealtimeIsTheInverseOfFromRealtime) {
  const RigClock clock(-123'456'789'000);
  for (int64_t rig : {clock.now(), clock.now() - 5'000'000'000, clock.now() + 1}) {
    // Two samples of REALTIME - MONOTONIC apart: equal but for a clock slew between them.
    EXPECT_LT(std::llabs(clock.from_realtime(clock.to_realtime(rig)) - rig), 1'000'000) << rig;
  }
}

TEST(RigClock, NowOnTheRealtimeClockIsNow) {
  const RigClock clock = RigClock::starting_at(42);
  const int64_t before = realtime_now_ns();
  const int64_t stamp = clock.to_realtime(clock.now());
  const int64_t after = realtime_now_ns();
  // Between the two reads, give or take the bracket of the REALTIME - MONOTONIC sample.
  EXPECT_GE(stamp, before - 1'000'000);
  EXPECT_LE(stamp, after + 1'000'000);
}

}  // namespace
}  // namespace tetrapulse::host
