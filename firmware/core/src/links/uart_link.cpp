#include "tetrapulse/fw/links/uart_link.hpp"

namespace tetrapulse::fw {

void UartLink::on_bytes(protocol::ByteView bytes, Tick rx, MessageSink& sink) {
  while (bytes.size > 0) {
    size_t consumed = 0;
    const protocol::ReceiveEvent event = decoder_.feed(bytes, &consumed);
    bytes = bytes.subview(consumed, bytes.size - consumed);
    if (event.kind == protocol::ReceiveKind::kError) {
      if (transport_errors_ != UINT16_MAX) ++transport_errors_;
    } else if (event.kind == protocol::ReceiveKind::kMessage) {
      ReceivedMessage m;
      m.bytes = event.message;
      m.rx_tick = rx;
      m.link = this;
      sink.on_message(m);
    }
    if (consumed == 0) break;
  }
}

protocol::Status UartLink::do_send(const ReplyPath&, protocol::ByteView message) {
  uint8_t frame[protocol::kUartMaxFrameSize];
  const protocol::Result<size_t> n = protocol::encode_uart_frame(message, frame, sizeof(frame));
  if (!n) return n.error();
  return port_.write(protocol::ByteView{frame, *n});
}

}  // namespace tetrapulse::fw
