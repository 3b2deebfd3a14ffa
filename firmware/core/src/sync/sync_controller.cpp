#include "tetrapulse/fw/sync/sync_controller.hpp"

namespace tetrapulse::fw {
namespace {

bool same_sync_fields(const protocol::Config& a, const protocol::Config& b) {
  return a.sync_source == b.sync_source && a.gpio_edge == b.gpio_edge &&
         a.gpio_edge_period_ns == b.gpio_edge_period_ns && a.gpio_edge_epoch_ns == b.gpio_edge_epoch_ns &&
         a.gpio_edge_numbering == b.gpio_edge_numbering;
}

ServoTuning tuning_for(protocol::SyncSource source) {
  return source == protocol::SyncSource::kCan ? ServoTuning::can() : ServoTuning::gpio();
}

}  // namespace

SyncController::SyncController(uint32_t tick_hz)
    : servo_(tick_hz), numberer_(tick_hz), pairing_(tick_hz), coarse_pairing_(tick_hz) {}

void SyncController::configure(const protocol::Config& config, Tick now) {
  if (configured_ && same_sync_fields(config, sync_fields_)) return;
  configured_ = true;
  sync_fields_ = config;
  source_ = config.sync_source;
  numberer_.configure(config, now);
  pairing_.reset();
  if (source_ == protocol::SyncSource::kNone) {
    servo_.stop();
  } else {
    servo_.restart(tuning_for(source_));
  }
}

void SyncController::on_edge(Tick captured) {
  if (source_ != protocol::SyncSource::kGpio) return;
  const NumberedEdge edge = numberer_.number(captured, servo_);
  if (edge.verdict == EdgeVerdict::kSpurious) {
    ++spurious_edges_;
    return;
  }
  if (edge.verdict != EdgeVerdict::kNumbered) return;
  if (edge.restart && servo_.acquired()) servo_.restart(tuning_for(source_));
  servo_.add_sample(captured, edge.rig_ns);
}

void SyncController::on_sync(uint16_t sync_seq, Tick rx, LinkKind link) {
  coarse_pairing_.on_sync(sync_seq, rx);
  if (link == LinkKind::kCan) pairing_.on_sync(sync_seq, rx);
}

void SyncController::on_follow_up(uint16_t sync_seq, int64_t tx_time_ns, Tick rx, LinkKind link) {
  // Coarse time for edge numbering, from any link: the Sync's reception when it pairs,
  // else this FollowUp's (late by the gap between the two, well under a frame period).
  const std::optional<SyncSample> coarse = coarse_pairing_.on_follow_up(sync_seq, tx_time_ns, rx);
  numberer_.set_coarse_time(coarse ? coarse->local : rx, tx_time_ns);
  if (link != LinkKind::kCan || source_ != protocol::SyncSource::kCan) return;
  const std::optional<SyncSample> sample = pairing_.on_follow_up(sync_seq, tx_time_ns, rx);
  if (sample) {
    servo_.add_sample(sample->local, sample->rig_ns);
  } else {
    ++unpaired_;
  }
}

void SyncController::report(Tick now, protocol::StatusReport& status) const {
  status.sync_source = source_;
  status.sync_state = servo_.state(now);
  status.offset_ns = servo_.offset_ns();
  status.rate_ppb = servo_.rate_ppb();
  status.holdover_ms = servo_.holdover_ms(now);
  status.sync_accepted = servo_.accepted();
  const uint64_t rejected = uint64_t{servo_.rejected()} + spurious_edges_ + unpaired_;
  status.sync_rejected = rejected > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(rejected);
}

}  // namespace tetrapulse::fw
