#pragma once
// The host's end of one simulated board's links, through the real transports: messages
// go out as CAN transfers (from node 0), USB bulk transfers or UART frames, and what the
// board sends back is reassembled and decoded the same way. Tests and the virtual rig
// talk to a SimBoard through it.
#include <cstdint>
#include <optional>
#include <vector>

#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::sim_board {

class HostPort {
 public:
  explicit HostPort(SimBoard& board);

  // Sends one encoded message at rig time t (CAN: to `can_destination`, priority by type).
  void send(fw::LinkKind link, protocol::ByteView message, int64_t rig_ns,
            uint8_t can_destination = protocol::kCanBroadcastNode);
  // Encodes and sends.
  void send(fw::LinkKind link, const protocol::Message& message, int64_t rig_ns,
            uint8_t can_destination = protocol::kCanBroadcastNode);
  // Messages the board sent on `link` since the last call, as bytes.
  std::vector<std::vector<uint8_t>> receive(fw::LinkKind link);

  // Sends `request` over `link` at the board's now() and returns the decoded answer with
  // its seq (kTimeout when none came).
  protocol::Result<protocol::Message> request(fw::LinkKind link, const protocol::Message& request);

 private:
  SimBoard& board_;
  protocol::CanTransferSender can_sender_{protocol::kCanHostNode};
  protocol::CanReceiveSession sessions_[4];
  protocol::CanTransferReceiver can_receiver_{sessions_, 4};
  protocol::UartFrameDecoder uart_decoder_;
};

}  // namespace tetrapulse::sim_board
