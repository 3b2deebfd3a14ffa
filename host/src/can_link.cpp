#include "tetrapulse/host/can_link.hpp"

#include <linux/can/error.h>

#include <random>

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {

using protocol::MessageType;

uint8_t can_priority_for(MessageType type) {
  if (type == MessageType::kUpdateChunk) return protocol::kCanPriorityBulk;
  if (protocol::is_time_sync(type)) return protocol::kCanPrioritySync;
  return protocol::is_response(type) ? protocol::kCanPriorityResponse : protocol::kCanPriorityRequest;
}

const char* can_controller_state_name(CanControllerState state) {
  switch (state) {
    case CanControllerState::kActive: return "error-active";
    case CanControllerState::kWarning: return "error-warning";
    case CanControllerState::kPassive: return "error-passive";
    case CanControllerState::kBusOff: return "bus-off";
  }
  return "unknown";
}

namespace {

// The controller's state after an error frame of `error_class` with `data` (error.h).
CanControllerState next_state(CanControllerState state, uint32_t error_class, const std::array<uint8_t, 8>& data) {
  if ((error_class & CAN_ERR_BUSOFF) != 0) return CanControllerState::kBusOff;
  if ((error_class & CAN_ERR_RESTARTED) != 0) return CanControllerState::kActive;
  if ((error_class & CAN_ERR_CRTL) != 0) {
    const uint8_t c = data[1];
    if ((c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) return CanControllerState::kPassive;
    if ((c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) return CanControllerState::kWarning;
    if ((c & CAN_ERR_CRTL_ACTIVE) != 0) return CanControllerState::kActive;
  }
  return state;
}

}  // namespace

std::string can_link_name(const std::string& interface_name, uint8_t peer_node) {
  return peer_node == protocol::kCanBroadcastNode ? fmt::format("can:{}:all", interface_name)
                                                  : fmt::format("can:{}:{}", interface_name, peer_node);
}

HostResult<std::unique_ptr<CanLink>> CanLink::open(const std::string& interface_name, uint8_t peer_node,
                                                   uint8_t local_node) {
  const std::string name = can_link_name(interface_name, peer_node);
  if (local_node == protocol::kCanBroadcastNode || local_node == peer_node) {
    return host_error(HostErrorKind::kBadInput, name, fmt::format("node {} cannot talk to node {}", local_node, peer_node));
  }
  const protocol::CanNodeFilters f = protocol::can_node_filters(local_node);
  SocketCanOptions options;
  options.filters = {f.addressed, f.broadcast};
  auto port = open_socketcan(interface_name, options);
  if (!port) {
    HostError e = port.error();
    e.device = name;
    return tl::unexpected(e);
  }
  // Transfer-id and seq from a random start (see the constructor): a repeat then needs both
  // to match, 1 in 32 × 256 for two runs within the transfer timeout.
  const uint32_t start = std::random_device{}();
  return std::make_unique<CanLink>(std::move(*port), local_node, peer_node, static_cast<uint8_t>(start),
                                   static_cast<uint8_t>(start >> 8));
}

CanLink::CanLink(std::unique_ptr<CanPort> port, uint8_t local_node, uint8_t peer_node, uint8_t first_transfer_id,
                 uint8_t first_seq)
    : Link(can_link_name(port->interface_name(), peer_node), first_seq),
      port_(std::move(port)),
      local_(local_node),
      peer_(peer_node),
      sender_(local_node, first_transfer_id),
      receiver_(sessions_, kSessions) {}

HostResult<void> CanLink::send_bytes(protocol::ByteView message) {
  if (bus_off_) {
    return host_error(HostErrorKind::kBusOff, name(), "the CAN controller is bus-off (restart the interface)");
  }
  if (message.size < protocol::kMessageHeaderSize) {
    return host_error(HostErrorKind::kBadInput, name(), fmt::format("a {}-byte message is too short", message.size));
  }
  const uint8_t priority = can_priority_for(static_cast<MessageType>(message[1]));
  HostError failure;
  const protocol::Status sent = sender_.send(priority, peer_, message, [&](const protocol::CanFrame& frame) {
    auto queued = port_->send(frame);
    if (queued) return protocol::Status{};
    failure = queued.error();
    failure.device = name();
    return protocol::Status{protocol::Error::kBusy};
  });
  if (sent) return {};
  if (!failure.message.empty()) return tl::unexpected(failure);
  return host_error(HostErrorKind::kBadInput, name(),
                    fmt::format("cannot send a {}-byte message: {}", message.size, protocol::error_name(sent.error())),
                    sent.error());
}

std::string CanLink::silence_hint() const {
  if (error_frames_ == 0) return {};
  return fmt::format(" ({} CAN error frames, the last: {}; the controller is {})", error_frames_,
                     can_error_class_names(last_error_class_), can_controller_state_name(state_));
}

HostResult<std::optional<RawMessage>> CanLink::receive_bytes(int64_t timeout_ns) {
  const int64_t deadline = monotonic_now_ns() + timeout_ns;
  for (;;) {
    const int64_t left = deadline - monotonic_now_ns();
    if (left < 0) return std::nullopt;
    auto event = port_->next(left);
    if (!event) {
      HostError e = event.error();
      e.device = name();
      return tl::unexpected(e);
    }
    if (!event->has_value()) return std::nullopt;
    const CanPortEvent& e = **event;
    if (e.kind == CanPortEvent::Kind::kError) {
      ++error_frames_;
      last_error_class_ = e.error_class;
      state_ = next_state(state_, e.error_class, e.error_data);
      if ((e.error_class & CAN_ERR_RESTARTED) != 0) bus_off_ = false;
      if ((e.error_class & CAN_ERR_BUSOFF) != 0) {
        bus_off_ = true;
        return host_error(HostErrorKind::kBusOff, name(), "the CAN controller went bus-off");
      }
      continue;
    }
    if (e.kind != CanPortEvent::Kind::kFrame || e.own) continue;
    const protocol::Result<protocol::CanId> id = protocol::unpack_can_id(e.frame.id);
    if (!id) {
      ++counters_.transport_errors;
      continue;
    }
    // Only what is addressed to us, from our peer (any board when the peer is broadcast).
    if (id->destination != local_ && id->destination != protocol::kCanBroadcastNode) continue;
    if (id->source == local_ || (peer_ != protocol::kCanBroadcastNode && id->source != peer_)) continue;
    const protocol::CanReceiveOutcome out = receiver_.accept(e.frame, e.timestamp_ns);
    if (out.verdict == protocol::CanFrameVerdict::kDropped || out.fault != protocol::CanFault::kNone) {
      ++counters_.transport_errors;
    }
    if (out.verdict != protocol::CanFrameVerdict::kComplete) continue;
    const protocol::ByteView m = out.transfer.message;
    return RawMessage{std::vector<uint8_t>(m.begin(), m.end()), out.transfer.timestamp_ns, out.transfer.id.source};
  }
}

}  // namespace tetrapulse::host
