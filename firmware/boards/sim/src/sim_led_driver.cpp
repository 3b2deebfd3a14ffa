#include "tetrapulse/sim_board/sim_led_driver.hpp"

#include <algorithm>

namespace tetrapulse::sim_board {

SimLedDriver::SimLedDriver(const fw::LocalClock& clock, uint32_t lead_ticks, size_t queue_depth,
                           uint16_t full_scale_ma)
    : clock_(clock), lead_ticks_(lead_ticks), depth_(queue_depth == 0 ? 1 : queue_depth), full_scale_ma_(full_scale_ma) {}

protocol::Status SimLedDriver::do_schedule(uint8_t index, uint16_t duty, fw::Tick at) {
  if (index >= fw::kLedCount) return protocol::Error::kBadValue;
  if (pending_[index].size() >= depth_) return protocol::Error::kBusy;
  if (at < clock_.now() + lead_ticks_) return protocol::Error::kInvalidState;
  if (!pending_[index].empty() && at < pending_[index].back().tick) return protocol::Error::kBadValue;
  pending_[index].push_back(Pending{at, duty});
  return {};
}

size_t SimLedDriver::do_pending(uint8_t index) const { return index < fw::kLedCount ? pending_[index].size() : 0; }

void SimLedDriver::do_cancel() {
  for (auto& q : pending_) q.clear();
}

void SimLedDriver::do_set_now(uint8_t index, uint16_t duty) {
  if (index >= fw::kLedCount) return;
  record(index, duty, clock_.now(), rig_now_);
}

std::optional<std::pair<uint8_t, fw::Tick>> SimLedDriver::next_due() const {
  std::optional<std::pair<uint8_t, fw::Tick>> best;
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    if (pending_[m].empty()) continue;
    if (!best || pending_[m].front().tick < best->second) best = std::make_pair(m, pending_[m].front().tick);
  }
  return best;
}

void SimLedDriver::apply_next(uint8_t marker, long double rig_ns) {
  if (pending_[marker].empty()) return;
  const Pending p = pending_[marker].front();
  pending_[marker].pop_front();
  record(marker, p.duty, p.tick, rig_ns);
}

void SimLedDriver::reset(long double rig_ns, fw::Tick tick) {
  do_cancel();
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    if (duty_[m] != 0) record(m, 0, tick, rig_ns);
  }
}

void SimLedDriver::record(uint8_t marker, uint16_t duty, fw::Tick tick, long double rig_ns) {
  duty_[marker] = duty;
  const AppliedLedChange change{marker, duty, tick, rig_ns};
  log_.push_back(change);
  per_marker_[marker].push_back(change);
}

void SimLedDriver::forget_before(long double rig_ns) {
  const auto before = [rig_ns](const AppliedLedChange& c) { return c.rig_ns < rig_ns; };
  for (std::vector<AppliedLedChange>& changes : per_marker_) {
    const auto first_kept = std::partition_point(changes.begin(), changes.end(), before);
    if (first_kept != changes.begin()) changes.erase(changes.begin(), std::prev(first_kept));
  }
  log_.erase(log_.begin(), std::partition_point(log_.begin(), log_.end(), before));
}

double SimLedDriver::mean_duty(uint8_t marker, long double t0, long double t1) const {
  if (!(t1 > t0)) return 0;
  const std::vector<AppliedLedChange>& changes = per_marker_[marker];
  // The change in force at t0: the last one at or before it (dark before the first).
  auto it = std::upper_bound(changes.begin(), changes.end(), t0,
                             [](long double t, const AppliedLedChange& c) { return t < c.rig_ns; });
  uint16_t level = it == changes.begin() ? 0 : std::prev(it)->duty;
  long double from = t0;
  long double sum = 0;
  for (; it != changes.end() && it->rig_ns < t1; ++it) {
    sum += (it->rig_ns - from) * level;
    from = it->rig_ns;
    level = it->duty;
  }
  sum += (t1 - from) * level;
  return static_cast<double>(sum / ((t1 - t0) * fw::kDutyFull));
}

}  // namespace tetrapulse::sim_board
