#pragma once
// A link to one board (or every board) on a CAN bus: messages as transfers of
// protocol/SPEC.md §4 through the protocol's CanTransferSender/Receiver, receive
// timestamps from the kernel (the first frame's, §4.4), error frames counted and
// bus-off reported as an error.
//
// A link is (interface, local node, peer node): the host is node 0 talking to board N;
// peer kCanBroadcastNode sends to every board and takes answers from any
// (ReceivedMessage::source_node says which). Several links may share an interface;
// each has its own socket.
#include <cstdint>
#include <memory>
#include <string>

#include "tetrapulse/host/can_port.hpp"
#include "tetrapulse/host/link.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"

namespace tetrapulse::host {

// The priority a message of `type` travels with (SPEC.md §4.1).
uint8_t can_priority_for(protocol::MessageType type);

// The host's CAN controller as its error frames tell it (linux/can/error.h): error-active,
// warning (an error counter past 96), error-passive (past 127), bus-off; a restart makes it
// error-active again.
enum class CanControllerState : uint8_t { kActive, kWarning, kPassive, kBusOff };
const char* can_controller_state_name(CanControllerState state);

class CanLink : public Link {
 public:
  static constexpr size_t kSessions = 8;

  // Opens a raw socket on `interface_name` with the acceptance filters of `local_node`.
  static HostResult<std::unique_ptr<CanLink>> open(const std::string& interface_name, uint8_t peer_node,
                                                   uint8_t local_node = protocol::kCanHostNode);
  // Over any port (tests use a fake); the port should already filter for `local_node`.
  // Transfer-ids start at `first_transfer_id`, seqs at `first_seq` (open() picks both at
  // random: a board ignores a single-frame request identical in tail byte and payload to
  // the previous one within its transfer timeout, SPEC.md §4.4, so two `tetrapulse status`
  // runs in a row must differ in one of them; random transfer-ids alone collide 1 in 32).
  CanLink(std::unique_ptr<CanPort> port, uint8_t local_node, uint8_t peer_node, uint8_t first_transfer_id = 0,
          uint8_t first_seq = 1);

  uint8_t local_node() const { return local_; }
  uint8_t peer_node() const { return peer_; }
  bool bus_off() const { return bus_off_; }
  CanControllerState controller_state() const { return state_; }
  uint32_t error_frames() const { return error_frames_; }
  const protocol::CanReceiverStats& receiver_stats() const { return receiver_.stats(); }

 protected:
  HostResult<void> send_bytes(protocol::ByteView message) override;
  HostResult<std::optional<RawMessage>> receive_bytes(int64_t timeout_ns) override;
  std::string silence_hint() const override;

 private:
  std::unique_ptr<CanPort> port_;
  uint8_t local_;
  uint8_t peer_;
  protocol::CanTransferSender sender_;
  protocol::CanReceiveSession sessions_[kSessions];
  protocol::CanTransferReceiver receiver_;
  bool bus_off_ = false;
  CanControllerState state_ = CanControllerState::kActive;
  uint32_t error_frames_ = 0;
  uint32_t last_error_class_ = 0;
};

// "can:vcan0:3", or "can:vcan0:all" for the broadcast node.
std::string can_link_name(const std::string& interface_name, uint8_t peer_node);

}  // namespace tetrapulse::host
