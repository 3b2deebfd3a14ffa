#pragma once
// A target board's clock: its notion of rig time, which sets the bit it plays.
// Times are nanoseconds of rig time (the camera host's clock, docs/rig-dataset.md).
//
// Locked (synchronized, outside sync loss):  b(t) = t + offset_ns
// Free-running (timebase not synchronized):  b(t) = offset_ns + t (1 + drift_ppm 1e-6)
// Sync lost over [s0, s1):                   b(t) = s0 + offset_ns + (t - s0)(1 + drift_ppm 1e-6)
//   (the board keeps counting with its crystal from where it last was locked, and
//   snaps back to b(t) = t + offset_ns when sync returns at s1).
#include <cstdint>
#include <utility>

#include "tetrapulse/sim/time_intervals.hpp"

namespace tetrapulse::sim {

// How a board is synchronized (what a simulated firmware board receives; the contract
// formula only needs free_running and the offset).
enum class BoardSync {
  kGpio,  // edges on its sync input at the camera's exposure starts
  kCan,   // Sync/FollowUp broadcasts over CAN
  kNone,  // no sync: free-running
};

struct BoardClockSpec {
  bool free_running = false;  // never synchronized: epoch and exact rate unknown to the localizer
  BoardSync sync = BoardSync::kGpio;  // kNone exactly when free_running
  double drift_ppm = 0;       // crystal error: board ns per rig ns is 1 + drift_ppm 1e-6
  int64_t offset_ns = 0;      // board time minus rig time when locked (or at rig time 0 when free-running)
  TimeIntervals sync_loss;    // rig-time intervals in which a synchronized board free-runs
};

class BoardClock {
 public:
  BoardClock() = default;
  explicit BoardClock(BoardClockSpec spec) : spec_(std::move(spec)) {}

  const BoardClockSpec& spec() const { return spec_; }

  // b(t): the board's notion of rig time at rig time t (both ns).
  double board_time(double t_ns) const;

  // Calls fn(a, b, board_at_a, rate) for consecutive pieces [a, b) covering [t0, t1),
  // on each of which b(t) = board_at_a + rate (t - a).
  template <typename Fn>
  void pieces(int64_t t0, int64_t t1, Fn&& fn) const {
    const double rate = 1.0 + spec_.drift_ppm * 1e-6;
    if (spec_.free_running) {
      fn(t0, t1, board_time(static_cast<double>(t0)), rate);
      return;
    }
    spec_.sync_loss.split(t0, t1, [&](int64_t a, int64_t b, bool lost) {
      fn(a, b, board_time(static_cast<double>(a)), lost ? rate : 1.0);
    });
  }

 private:
  BoardClockSpec spec_;
};

}  // namespace tetrapulse::sim
