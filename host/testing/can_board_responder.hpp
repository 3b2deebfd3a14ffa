#pragma once
// A BoardResponder on a CAN bus: reassembles transfers addressed to its node (the node id
// of its running configuration) with the protocol's receiver and answers with the
// protocol's sender (SPEC.md §4). Frames in, frames out: a fake bus or a SocketCAN port
// carries them.
#include <vector>

#include "board_responder.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"

namespace tetrapulse::host::testing {

class CanBoardResponder {
 public:
  explicit CanBoardResponder(ResponderIdentity identity = {});

  // One frame from the bus at `now_ns`; returns the frames of its answer, in bus order.
  std::vector<protocol::CanFrame> on_frame(const protocol::CanFrame& frame, int64_t now_ns);

  BoardResponder& responder() { return responder_; }
  uint8_t node() const { return responder_.running_config().node_id; }

 private:
  BoardResponder responder_;
  protocol::CanReceiveSession sessions_[4];
  protocol::CanTransferReceiver receiver_;
  protocol::CanTransferSender sender_;
};

}  // namespace tetrapulse::host::testing
