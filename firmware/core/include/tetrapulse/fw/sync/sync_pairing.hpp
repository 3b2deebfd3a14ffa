#pragma once
// Pairs a Sync with its FollowUp (SPEC.md §2.4): the Sync's reception tick and the
// FollowUp's tx_time_ns are one servo sample. A FollowUp whose sync_seq is not that of
// the last Sync received, one that comes after the pair was already used, or one more
// than kMaxFollowUpDelay after its Sync is dropped.
#include <cstdint>
#include <optional>

#include "tetrapulse/fw/clock/tick.hpp"

namespace tetrapulse::fw {

struct SyncSample {
  Tick local = 0;      // reception of the Sync
  int64_t rig_ns = 0;  // the master's transmit time of that Sync
};

class SyncPairing {
 public:
  explicit SyncPairing(uint32_t tick_hz) : max_delay_ticks_(tick_hz) {}  // 1 s

  void on_sync(uint16_t sync_seq, Tick rx);
  std::optional<SyncSample> on_follow_up(uint16_t sync_seq, int64_t tx_time_ns, Tick rx);
  void reset() { have_sync_ = false; }

 private:
  uint64_t max_delay_ticks_;
  bool have_sync_ = false;
  uint16_t seq_ = 0;
  Tick rx_ = 0;
};

}  // namespace tetrapulse::fw
