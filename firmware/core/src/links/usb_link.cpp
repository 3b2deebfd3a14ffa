#include "tetrapulse/fw/links/usb_link.hpp"

namespace tetrapulse::fw {

void UsbLink::deliver(protocol::ByteView message, Tick rx, uint8_t path, MessageSink& sink) {
  ReceivedMessage m;
  m.bytes = message;
  m.rx_tick = rx;
  m.link = this;
  m.reply.peer = path;
  sink.on_message(m);
}

void UsbLink::on_bulk_transfer(protocol::ByteView transfer, Tick rx, MessageSink& sink) {
  const protocol::Result<protocol::ByteView> message = protocol::decode_usb_bulk_frame(transfer);
  if (!message) {
    if (transport_errors_ != UINT16_MAX) ++transport_errors_;
    return;
  }
  deliver(*message, rx, kUsbBulkPath, sink);
}

void UsbLink::on_bulk_packet(protocol::ByteView packet, Tick rx, MessageSink& sink) {
  const protocol::ReceiveEvent event = packets_.push_packet(packet);
  if (event.kind == protocol::ReceiveKind::kError) {
    if (transport_errors_ != UINT16_MAX) ++transport_errors_;
  } else if (event.kind == protocol::ReceiveKind::kMessage) {
    deliver(event.message, rx, kUsbBulkPath, sink);
  }
}

void UsbLink::on_control_message(protocol::ByteView message, Tick rx, MessageSink& sink) {
  if (message.size < 3 || message.size > protocol::kMaxMessageSize) {
    if (transport_errors_ != UINT16_MAX) ++transport_errors_;
    return;
  }
  deliver(message, rx, kUsbControlPath, sink);
}

protocol::Result<size_t> UsbLink::take_control_response(uint8_t* out, size_t capacity) {
  if (control_count_ == 0) return size_t{0};
  const Pending& p = control_[control_head_];
  if (p.size > capacity) return protocol::Error::kBufferTooSmall;
  for (size_t i = 0; i < p.size; ++i) out[i] = p.bytes[i];
  control_head_ = (control_head_ + 1) % kControlQueue;
  --control_count_;
  return static_cast<size_t>(p.size);
}

protocol::Status UsbLink::do_send(const ReplyPath& to, protocol::ByteView message) {
  if (message.size < 3 || message.size > protocol::kMaxMessageSize) return protocol::Error::kBadLength;
  if (to.peer == kUsbControlPath) {
    if (control_count_ == kControlQueue) return protocol::Error::kBusy;
    Pending& p = control_[(control_head_ + control_count_) % kControlQueue];
    for (size_t i = 0; i < message.size; ++i) p.bytes[i] = message[i];
    p.size = static_cast<uint16_t>(message.size);
    ++control_count_;
    return {};
  }
  uint8_t transfer[protocol::kUsbBulkMaxTransfer];
  const protocol::Result<size_t> n = protocol::encode_usb_bulk_frame(message, transfer, sizeof(transfer));
  if (!n) return n.error();
  return pipe_.send_bulk(protocol::ByteView{transfer, *n});
}

}  // namespace tetrapulse::fw
