#include "can_board_responder.hpp"

#include "tetrapulse/host/can_link.hpp"

namespace tetrapulse::host::testing {

CanBoardResponder::CanBoardResponder(ResponderIdentity identity)
    : responder_(identity), receiver_(sessions_, 4), sender_(identity.node_id) {}

std::vector<protocol::CanFrame> CanBoardResponder::on_frame(const protocol::CanFrame& frame, int64_t now_ns) {
  std::vector<protocol::CanFrame> out;
  const protocol::CanNodeFilters filters = protocol::can_node_filters(node());
  if (!protocol::can_filter_matches(filters.addressed, frame.id) &&
      !protocol::can_filter_matches(filters.broadcast, frame.id)) {
    return out;
  }
  const protocol::CanReceiveOutcome in = receiver_.accept(frame, now_ns);
  if (in.verdict != protocol::CanFrameVerdict::kComplete) return out;
  const uint8_t requester = in.transfer.id.source;
  auto reply = responder_.answer(in.transfer.message, now_ns);
  if (!reply) return out;
  if (sender_.source() != node()) sender_ = protocol::CanTransferSender(node());  // SetConfig moved us
  const protocol::ByteView m{reply->data(), reply->size()};
  sender_.send(can_priority_for(static_cast<protocol::MessageType>(m[1])), requester, m,
               [&](const protocol::CanFrame& f) {
                 out.push_back(f);
                 return protocol::Status{};
               });
  return out;
}

}  // namespace tetrapulse::host::testing
