#include "tetrapulse/protocol/usb_control.hpp"

namespace tetrapulse::protocol {

Status check_usb_message_out(uint16_t w_length) {
  return w_length >= 3 && w_length <= kMaxMessageSize ? Status{} : Error::kBadLength;
}

Status UsbMessageOutReceiver::begin(uint16_t w_length) {
  reset();
  const Status s = check_usb_message_out(w_length);
  if (s.ok()) expected_ = w_length;
  return s;
}

void UsbMessageOutReceiver::reset() {
  expected_ = 0;
  size_ = 0;
}

ReceiveEvent UsbMessageOutReceiver::push_packet(ByteView packet) {
  if (expected_ == 0 || packet.size > kUsbMaxPacketSize) {
    reset();
    return ReceiveEvent::failed(Error::kBadFraming);
  }
  if (packet.size > expected_ - size_) {
    reset();
    return ReceiveEvent::failed(Error::kBadLength);
  }
  for (size_t i = 0; i < packet.size; ++i) buffer_[size_ + i] = packet[i];
  size_ += packet.size;
  if (size_ == expected_) {
    const size_t size = size_;
    reset();
    return ReceiveEvent::received(ByteView{buffer_, size});
  }
  if (packet.size < kUsbMaxPacketSize) {
    reset();
    return ReceiveEvent::failed(Error::kTruncated);
  }
  return ReceiveEvent::nothing();
}

Status check_usb_message_in(uint16_t w_length, size_t pending_size) {
  return pending_size <= w_length ? Status{} : Error::kBufferTooSmall;
}

}  // namespace tetrapulse::protocol
