#pragma once
// The CAN transport of SPEC.md §4 on top of a raw CAN controller: reassembles
// transfers addressed to this node (or broadcast) into messages, segments responses.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/can_id.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

// Hardware seam: a CAN controller (stm32f405: bxCAN; boards/sim: the simulated bus).
class CanBus {
 public:
  // Queues one frame for transmission; frames leave in the order given (a transfer's
  // frames must not be reordered). The queue holds a whole transfer
  // (kCanMaxFramesPerTransfer frames); kBusy when it is full.
  protocol::Status send(const protocol::CanFrame& frame) { return do_send(frame); }
  // Accept only frames matching these (SPEC.md §4.1); called whenever the node id changes.
  void set_filters(const protocol::CanNodeFilters& filters) { do_set_filters(filters); }
  // Error frames / error counter events seen since reset (saturating).
  uint16_t error_count() const { return do_error_count(); }
  bool bus_off() const { return do_bus_off(); }

 protected:
  ~CanBus() = default;

 private:
  virtual protocol::Status do_send(const protocol::CanFrame& frame) = 0;
  virtual void do_set_filters(const protocol::CanNodeFilters& filters) = 0;
  virtual uint16_t do_error_count() const = 0;
  virtual bool do_bus_off() const = 0;
};

class CanLink final : public MessageLink {
 public:
  static constexpr size_t kSessions = 4;

  // `tick_hz`: the local counter rate (the transfer timeout, 1 s, is counted in ticks).
  CanLink(CanBus& bus, uint32_t tick_hz, uint8_t node);

  // Answers come from `node`; frames to other nodes are ignored. Sets the bus filters.
  void set_node(uint8_t node);
  uint8_t node() const { return node_; }

  // One frame received at local tick `rx` (its capture time, not when it was read).
  // A transfer it completes goes to `sink` with the tick of its first frame.
  void on_frame(const protocol::CanFrame& frame, Tick rx, MessageSink& sink);

  // Frames dropped by the transport (bad identifier, toggle, CRC ...), saturating.
  uint16_t transport_errors() const { return transport_errors_; }
  uint16_t bus_errors() const { return bus_.error_count(); }
  bool bus_off() const { return bus_.bus_off(); }

 private:
  LinkKind do_kind() const override { return LinkKind::kCan; }
  protocol::Status do_send(const ReplyPath& to, protocol::ByteView message) override;

  CanBus& bus_;
  uint8_t node_;
  protocol::CanReceiveSession sessions_[kSessions];
  protocol::CanTransferReceiver receiver_;
  protocol::CanTransferSender sender_;
  uint16_t transport_errors_ = 0;
};

}  // namespace tetrapulse::fw
