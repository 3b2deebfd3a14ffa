#include "tetrapulse/protocol/usb_bulk_frame.hpp"

namespace tetrapulse::protocol {

Result<size_t> encode_usb_bulk_frame(ByteView message, uint8_t* out, size_t capacity) {
  if (message.size < 3 || message.size > kMaxMessageSize) return Error::kBadLength;
  ByteWriter w(out, capacity);
  w.u16(static_cast<uint16_t>(message.size));
  w.bytes(message.data, message.size);
  if (!w.ok()) return Error::kBufferTooSmall;
  return w.size();
}

Result<ByteView> decode_usb_bulk_frame(ByteView transfer) {
  ByteReader r(transfer);
  const uint16_t length = r.u16();
  if (!r.ok()) return r.error();
  if (length != transfer.size - kUsbBulkHeaderSize || length > kMaxMessageSize || length < 3) {
    return Error::kBadLength;
  }
  return transfer.subview(kUsbBulkHeaderSize, length);
}

void UsbBulkFrameReceiver::reset() {
  size_ = 0;
  skipping_ = false;
}

ReceiveEvent UsbBulkFrameReceiver::push_packet(ByteView packet) {
  if (packet.size > kUsbMaxPacketSize) {
    reset();
    return ReceiveEvent::failed(Error::kBadFraming);
  }
  const bool last = packet.size < kUsbMaxPacketSize;
  if (skipping_) {
    if (last) reset();
    return ReceiveEvent::nothing();
  }
  if (size_ + packet.size > sizeof(buffer_)) {
    if (last) {
      reset();
    } else {
      skipping_ = true;
    }
    return ReceiveEvent::failed(Error::kBadLength);
  }
  for (size_t i = 0; i < packet.size; ++i) buffer_[size_ + i] = packet[i];
  size_ += packet.size;
  if (!last) return ReceiveEvent::nothing();

  const size_t size = size_;
  reset();
  if (size == 0) return ReceiveEvent::nothing();
  const Result<ByteView> message = decode_usb_bulk_frame(ByteView{buffer_, size});
  if (!message) return ReceiveEvent::failed(message.error());
  return ReceiveEvent::received(*message);
}

}  // namespace tetrapulse::protocol
