#include "tetrapulse/host/sim_can_bus.hpp"

#include "tetrapulse/protocol/can_id.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::host {

void SimCanBus::attach(std::shared_ptr<sim_board::SimBoard> board, std::function<int64_t()> sync_latency,
                       std::function<bool(int64_t)> connected) {
  nodes_.push_back(Node{std::move(board), std::move(sync_latency), std::move(connected)});
}

void SimCanBus::set_time(int64_t rig_ns) {
  if (rig_ns > now_) now_ = rig_ns;
  events_.clear();  // stamps nobody read (of multi-frame transfers) are stale by now
}

HostResult<uint32_t> SimCanBus::do_send(const protocol::CanFrame& frame) {
  const auto id = protocol::unpack_can_id(frame.id & protocol::kCanExtendedIdMask);
  const bool sync = id.ok() && id->type == static_cast<uint8_t>(protocol::MessageType::kSync);
  for (Node& n : nodes_) {
    if (!n.connected(now_)) continue;
    n.board->can_frame(frame, now_ + (sync ? n.sync_latency() : 0));
  }
  ++frames_sent_;
  CanPortEvent stamp;
  stamp.kind = CanPortEvent::Kind::kTxTimestamp;
  stamp.timestamp_ns = now_ + kStampOffsetNs;
  stamp.tx_key = next_key_++;
  events_.push_back(stamp);
  return stamp.tx_key;
}

HostResult<std::optional<CanPortEvent>> SimCanBus::do_next(int64_t /*timeout_ns*/) {
  if (events_.empty()) return std::optional<CanPortEvent>{};
  CanPortEvent e = events_.front();
  events_.pop_front();
  if (e.kind == CanPortEvent::Kind::kTxTimestamp) now_ += turnaround_ns_;
  return std::optional<CanPortEvent>{e};
}

}  // namespace tetrapulse::host
