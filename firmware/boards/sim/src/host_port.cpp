#include "tetrapulse/sim_board/host_port.hpp"

#include "tetrapulse/protocol/usb_bulk_frame.hpp"

namespace tetrapulse::sim_board {

HostPort::HostPort(SimBoard& board) : board_(board) {}

void HostPort::send(fw::LinkKind link, protocol::ByteView message, int64_t rig_ns, uint8_t can_destination) {
  switch (link) {
    case fw::LinkKind::kCan: {
      const auto type = static_cast<protocol::MessageType>(message.size > 1 ? message[1] : 0);
      uint8_t priority = protocol::kCanPriorityRequest;
      if (protocol::is_time_sync(type)) priority = protocol::kCanPrioritySync;
      if (type == protocol::MessageType::kUpdateChunk) priority = protocol::kCanPriorityBulk;
      can_sender_.send(priority, can_destination, message, [&](const protocol::CanFrame& frame) {
        board_.can_frame(frame, rig_ns);
        return protocol::Status{};
      });
      break;
    }
    case fw::LinkKind::kUsb: {
      uint8_t transfer[protocol::kUsbBulkMaxTransfer];
      const protocol::Result<size_t> n = protocol::encode_usb_bulk_frame(message, transfer, sizeof(transfer));
      if (n) board_.usb_bulk(protocol::ByteView{transfer, *n}, rig_ns);
      break;
    }
    case fw::LinkKind::kUart: {
      uint8_t frame[protocol::kUartMaxFrameSize];
      const protocol::Result<size_t> n = protocol::encode_uart_frame(message, frame, sizeof(frame));
      if (n) board_.uart_bytes(protocol::ByteView{frame, *n}, rig_ns);
      break;
    }
  }
}

void HostPort::send(fw::LinkKind link, const protocol::Message& message, int64_t rig_ns, uint8_t can_destination) {
  uint8_t buf[protocol::kMaxMessageSize];
  protocol::ByteWriter out(buf, sizeof(buf));
  if (!protocol::encode(message, out)) return;
  send(link, out.view(), rig_ns, can_destination);
}

std::vector<std::vector<uint8_t>> HostPort::receive(fw::LinkKind link) {
  std::vector<std::vector<uint8_t>> messages;
  switch (link) {
    case fw::LinkKind::kCan:
      for (const protocol::CanFrame& frame : board_.take_can_frames()) {
        const protocol::CanReceiveOutcome o = can_receiver_.accept(frame, board_.now());
        if (o.verdict == protocol::CanFrameVerdict::kComplete) {
          messages.emplace_back(o.transfer.message.begin(), o.transfer.message.end());
        }
      }
      break;
    case fw::LinkKind::kUsb:
      for (const std::vector<uint8_t>& t : board_.take_usb_bulk()) {
        const protocol::Result<protocol::ByteView> m = protocol::decode_usb_bulk_frame(protocol::ByteView{t.data(), t.size()});
        if (m) messages.emplace_back(m->begin(), m->end());
      }
      break;
    case fw::LinkKind::kUart: {
      const std::vector<uint8_t> bytes = board_.take_uart_bytes();
      for (uint8_t b : bytes) {
        const protocol::ReceiveEvent e = uart_decoder_.push(b);
        if (e.kind == protocol::ReceiveKind::kMessage) messages.emplace_back(e.message.begin(), e.message.end());
      }
      break;
    }
  }
  return messages;
}

protocol::Result<protocol::Message> HostPort::request(fw::LinkKind link, const protocol::Message& request) {
  send(link, request, board_.now(), link == fw::LinkKind::kCan ? board_.options().node_id : protocol::kCanBroadcastNode);
  for (const std::vector<uint8_t>& bytes : receive(link)) {
    const protocol::Result<protocol::Message> m = protocol::decode(protocol::ByteView{bytes.data(), bytes.size()});
    if (m && m->seq == request.seq) return m;
  }
  return protocol::Error::kTimeout;
}

}  // namespace tetrapulse::sim_board
