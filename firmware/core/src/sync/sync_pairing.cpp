#include "tetrapulse/fw/sync/sync_pairing.hpp"

namespace tetrapulse::fw {

void SyncPairing::on_sync(uint16_t sync_seq, Tick rx) {
  have_sync_ = true;
  seq_ = sync_seq;
  rx_ = rx;
}

std::optional<SyncSample> SyncPairing::on_follow_up(uint16_t sync_seq, int64_t tx_time_ns, Tick rx) {
  if (!have_sync_ || sync_seq != seq_ || rx < rx_ || rx - rx_ > max_delay_ticks_) return std::nullopt;
  have_sync_ = false;  // one FollowUp per Sync: a repeat is stale
  return SyncSample{rx_, tx_time_ns};
}

}  // namespace tetrapulse::fw
