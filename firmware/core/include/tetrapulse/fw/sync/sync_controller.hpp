#pragma once
// Everything that disciplines the board's clock, behind the configured sync source:
// GPIO edges (numbered, then fed to the servo), CAN Sync/FollowUp pairs (paired, then
// fed to the servo), FollowUp as coarse time for GPIO edge numbering. With sync_source
// none the board free-runs on its last mapping.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/fw/sync/clock_servo.hpp"
#include "tetrapulse/fw/sync/gpio_edge_numberer.hpp"
#include "tetrapulse/fw/sync/sync_pairing.hpp"
#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::fw {

class SyncController {
 public:
  explicit SyncController(uint32_t tick_hz);

  // Takes the sync fields of `config`; restarts acquisition only when they changed.
  void configure(const protocol::Config& config, Tick now);

  void on_edge(Tick captured);
  void on_sync(uint16_t sync_seq, Tick rx, LinkKind link);
  void on_follow_up(uint16_t sync_seq, int64_t tx_time_ns, Tick rx, LinkKind link);

  const ClockServo& servo() const { return servo_; }
  protocol::SyncSource source() const { return source_; }
  // The sync fields of StatusReport.
  void report(Tick now, protocol::StatusReport& status) const;

 private:
  ClockServo servo_;
  GpioEdgeNumberer numberer_;
  SyncPairing pairing_;       // CAN: servo samples
  SyncPairing coarse_pairing_;  // any link: coarse time
  protocol::SyncSource source_ = protocol::SyncSource::kNone;
  protocol::Config sync_fields_;
  bool configured_ = false;
  uint32_t spurious_edges_ = 0;  // edges refused before they became samples
  uint32_t unpaired_ = 0;        // CAN FollowUps without their Sync (or stale)
};

}  // namespace tetrapulse::fw
