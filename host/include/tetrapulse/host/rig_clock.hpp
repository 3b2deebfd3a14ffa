#pragma once
// Rig time on the host (integer nanoseconds, DESIGN.md "the rig time base").
//
// The host that is the sync master defines rig time as its CLOCK_MONOTONIC plus a
// fixed offset chosen when the master starts:
//
//   rig_ns = monotonic_ns + offset_ns
//
// CLOCK_MONOTONIC, not CLOCK_REALTIME, because rig time must never jump: NTP may
// step the wall clock, and a step would break every board's clock servo. Kernel
// timestamps arrive on two clocks and are converted here, once, consistently:
//  - GPIO line events (libgpiod 1.6, uAPI v1, Linux >= 5.7): CLOCK_MONOTONIC, used as they are;
//  - SocketCAN SO_TIMESTAMPING / SO_TIMESTAMPNS software stamps: CLOCK_REALTIME, mapped
//    through the current REALTIME - MONOTONIC difference, sampled when converting
//    (a stamp is converted within milliseconds of being taken, so a later NTP step
//    cannot separate the two).
#include <cstdint>

namespace tetrapulse::host {

// Current CLOCK_MONOTONIC / CLOCK_REALTIME in ns.
int64_t monotonic_now_ns();
int64_t realtime_now_ns();
// CLOCK_REALTIME - CLOCK_MONOTONIC now, from a monotonic read on either side of a
// realtime read, the tightest of three (protocol/clock_bracket.hpp: error below half the
// bracket, well under a microsecond).
int64_t realtime_minus_monotonic_ns();
// A CLOCK_REALTIME kernel timestamp on CLOCK_MONOTONIC.
int64_t monotonic_from_realtime_ns(int64_t realtime_ns);

class RigClock {
 public:
  // rig_ns = monotonic_ns + offset_ns.
  explicit RigClock(int64_t offset_ns = 0) : offset_ns_(offset_ns) {}
  // A clock that reads `rig_now_ns` at this instant.
  static RigClock starting_at(int64_t rig_now_ns);

  int64_t offset_ns() const { return offset_ns_; }
  int64_t now() const { return from_monotonic(monotonic_now_ns()); }
  int64_t from_monotonic(int64_t monotonic_ns) const { return monotonic_ns + offset_ns_; }
  int64_t to_monotonic(int64_t rig_ns) const { return rig_ns - offset_ns_; }
  int64_t from_realtime(int64_t realtime_ns) const { return from_monotonic(monotonic_from_realtime_ns(realtime_ns)); }
  // A rig time on CLOCK_REALTIME, the clock ROS 2 nodes stamp messages with (through
  // the REALTIME - MONOTONIC difference now: for times within seconds of now).
  int64_t to_realtime(int64_t rig_ns) const { return to_monotonic(rig_ns) + realtime_minus_monotonic_ns(); }

 private:
  int64_t offset_ns_;
};

}  // namespace tetrapulse::host
