#pragma once
// Gives each captured sync edge its rig time (Config §2.5): edge k happens at
// gpio_edge_epoch_ns + k * gpio_edge_period_ns. How k is found:
//   nearest coarse time: k = round((coarse rig time - epoch) / period), the coarse rig
//     time from FollowUp over any link (set_coarse_time);
//   count after gap: k = 0 at the first edge after a gap of at least 2 periods (counted
//     from when capture started, for the first edge), then +1 per edge.
// Once the servo has acquired, k comes from the board's own disciplined clock (nearest
// edge), which is what makes a missed edge harmless; an edge less than half a period
// after the previous one, or numbered like an edge already seen, is spurious.
// Counting after gap, a gap of fewer than kCountRestartGapPeriods periods while the
// servo tracks the edges is taken for missed edges, not a restart of the count (SPEC.md
// says 2 periods; a single missed edge makes such a gap, and must not shift the time base).
#include <cstdint>
#include <optional>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/sync/clock_servo.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::fw {

constexpr int64_t kCountRestartGapPeriods = 4;

enum class EdgeVerdict : uint8_t {
  kNumbered,   // rig time found
  kUnnumbered, // no coarse time yet, or waiting for the gap that starts the count
  kSpurious,   // too soon after the previous edge, or a second edge with the same number
};

struct NumberedEdge {
  EdgeVerdict verdict = EdgeVerdict::kUnnumbered;
  int64_t rig_ns = 0;  // when kNumbered
  bool restart = false; // counting after gap: this edge restarted the count (k = 0)
};

class GpioEdgeNumberer {
 public:
  explicit GpioEdgeNumberer(uint32_t tick_hz) : nominal_(tick_hz) {}

  // New edge rule; forgets earlier edges. `now` is when capture (re)starts.
  void configure(const protocol::Config& config, Tick now);
  // A coarse rig time: rig time `rig_ns` at local tick `local` (FollowUp).
  void set_coarse_time(Tick local, int64_t rig_ns);

  NumberedEdge number(Tick local, const ClockServo& servo);

 private:
  int64_t nominal_ns(Tick from, Tick to) const;
  int64_t edge_time(int64_t k) const;
  int64_t nearest_k(int64_t rig_ns) const;

  ClockMapping nominal_;  // the counter at its nominal rate, for gaps between edges
  int64_t epoch_ns_ = 0;
  int64_t period_ns_ = 1;
  protocol::GpioEdgeNumbering numbering_ = protocol::GpioEdgeNumbering::kNearestCoarseTime;
  Tick started_ = 0;
  bool have_coarse_ = false;
  Tick coarse_local_ = 0;
  int64_t coarse_rig_ = 0;
  bool have_last_ = false;
  Tick last_local_ = 0;
  int64_t last_k_ = 0;
  bool counting_ = false;
};

}  // namespace tetrapulse::fw
