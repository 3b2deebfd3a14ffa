#include "tetrapulse/protocol/uart_frame.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {

Result<size_t> encode_uart_frame(ByteView message, uint8_t* out, size_t capacity) {
  if (message.size < 3 || message.size > kMaxMessageSize) return Error::kBadLength;
  if (capacity == 0) return Error::kBufferTooSmall;
  const uint16_t crc = crc16_ccitt(message.data, message.size);
  CobsEncoder encoder(out, capacity - 1);  // room for the delimiter
  encoder.put(message);
  encoder.put(static_cast<uint8_t>(crc));
  encoder.put(static_cast<uint8_t>(crc >> 8));
  const Result<size_t> size = encoder.finish();
  if (!size) return size.error();
  out[*size] = kUartDelimiter;
  return *size + 1;
}

void UartFrameDecoder::reset() {
  cobs_.reset();
  size_ = 0;
  in_frame_ = false;
  skipping_ = false;
}

ReceiveEvent UartFrameDecoder::push(uint8_t byte) {
  if (byte != kUartDelimiter) {
    if (skipping_) return ReceiveEvent::nothing();
    in_frame_ = true;
    uint8_t decoded = 0;
    if (!cobs_.feed(byte, &decoded)) return ReceiveEvent::nothing();
    if (size_ == sizeof(buffer_)) {
      skipping_ = true;
      return ReceiveEvent::failed(Error::kBadLength);
    }
    buffer_[size_++] = decoded;
    return ReceiveEvent::nothing();
  }

  // A delimiter ends the frame.
  const bool was_frame = in_frame_ && !skipping_;
  const bool complete = cobs_.complete();
  const size_t size = size_;
  reset();
  if (!was_frame) return ReceiveEvent::nothing();
  if (!complete) return ReceiveEvent::failed(Error::kBadFraming);
  if (size < 3 + kUartCrcSize) return ReceiveEvent::failed(Error::kBadLength);
  const size_t message_size = size - kUartCrcSize;
  const uint16_t crc = static_cast<uint16_t>(buffer_[message_size] | (buffer_[message_size + 1] << 8));
  if (crc16_ccitt(buffer_, message_size) != crc) return ReceiveEvent::failed(Error::kBadCrc);
  return ReceiveEvent::received(ByteView{buffer_, message_size});
}

ReceiveEvent UartFrameDecoder::feed(ByteView bytes, size_t* consumed) {
  size_t i = 0;
  ReceiveEvent event;
  while (i < bytes.size && event.kind == ReceiveKind::kNothing) event = push(bytes[i++]);
  if (consumed != nullptr) *consumed = i;
  return event;
}

}  // namespace tetrapulse::protocol
