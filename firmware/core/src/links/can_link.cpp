#include "tetrapulse/fw/links/can_link.hpp"

namespace tetrapulse::fw {

CanLink::CanLink(CanBus& bus, uint32_t tick_hz, uint8_t node)
    : bus_(bus), node_(node), receiver_(sessions_, kSessions, static_cast<int64_t>(tick_hz)), sender_(node) {
  bus_.set_filters(protocol::can_node_filters(node));
}

void CanLink::set_node(uint8_t node) {
  if (node == node_) return;
  node_ = node;
  sender_ = protocol::CanTransferSender(node);
  receiver_.reset();
  bus_.set_filters(protocol::can_node_filters(node));
}

void CanLink::on_frame(const protocol::CanFrame& frame, Tick rx, MessageSink& sink) {
  const protocol::Result<protocol::CanId> id = protocol::unpack_can_id(frame.id);
  if (!id) {
    if (transport_errors_ != UINT16_MAX) ++transport_errors_;
    return;
  }
  if (id->destination != node_ && id->destination != protocol::kCanBroadcastNode) return;  // not ours
  const protocol::CanReceiveOutcome outcome = receiver_.accept(frame, static_cast<int64_t>(rx));
  if (outcome.verdict == protocol::CanFrameVerdict::kDropped ||
      (outcome.fault != protocol::CanFault::kNone && outcome.verdict != protocol::CanFrameVerdict::kDuplicate)) {
    if (transport_errors_ != UINT16_MAX) ++transport_errors_;
  }
  if (outcome.verdict != protocol::CanFrameVerdict::kComplete) return;
  const protocol::CanReceivedTransfer& t = outcome.transfer;
  ReceivedMessage m;
  m.bytes = t.message;
  m.rx_tick = static_cast<Tick>(t.timestamp_ns);
  m.link = this;
  m.reply.peer = t.id.source;
  m.reply.local = t.id.destination == protocol::kCanBroadcastNode ? node_ : t.id.destination;
  sink.on_message(m);
}

protocol::Status CanLink::do_send(const ReplyPath& to, protocol::ByteView message) {
  auto sink = [this](const protocol::CanFrame& frame) { return bus_.send(frame); };
  if (to.local == node_ || to.local == 0 || to.local == protocol::kCanBroadcastNode) {
    return sender_.send(protocol::kCanPriorityResponse, to.peer, message, sink);
  }
  // The request was addressed to the node id we had before a SetConfig changed it:
  // answer from that id, so the requester recognises the answer.
  protocol::CanTransferSender former(to.local);
  return former.send(protocol::kCanPriorityResponse, to.peer, message, sink);
}

}  // namespace tetrapulse::fw
