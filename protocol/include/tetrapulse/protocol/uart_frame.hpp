#pragma once
// UART framing (SPEC.md §6): frame = COBS(message ‖ CRC-16/CCITT-FALSE(message),
// CRC little-endian) followed by one 0x00 delimiter.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/cobs.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/receive_event.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

constexpr uint8_t kUartDelimiter = 0x00;
constexpr size_t kUartCrcSize = 2;

// Largest frame for a message of `message_size` bytes, delimiter included.
constexpr size_t uart_max_frame_size(size_t message_size) {
  return cobs_max_encoded_size(message_size + kUartCrcSize) + 1;
}
constexpr size_t kUartMaxFrameSize = uart_max_frame_size(kMaxMessageSize);

// Writes the frame of `message` (3..kMaxMessageSize bytes) into `out`; returns its size.
// kBadLength for a message out of range, kBufferTooSmall when `capacity` is short
// (uart_max_frame_size(message.size) always suffices).
Result<size_t> encode_uart_frame(ByteView message, uint8_t* out, size_t capacity);

// Splits a byte stream into messages. Each 0x00 ends a frame; empty frames (repeated
// delimiters) are ignored, so a sender may send 0x00 at any time to flush line noise.
// An invalid frame gives one kError event:
//   kBadFraming  the COBS encoding ends mid-block
//   kBadLength   the decoded frame is shorter than 3 + 2 bytes, or longer than
//                kMaxMessageSize + 2 (reported as soon as it overflows; the rest of
//                the frame up to the next 0x00 is skipped)
//   kBadCrc      the CRC does not match
// and decoding continues with the next byte after the 0x00, so no following frame is lost.
class UartFrameDecoder {
 public:
  // Takes one byte.
  ReceiveEvent push(uint8_t byte);
  // Takes bytes until one ends a frame or the input runs out; `*consumed` says how many
  // were taken. Call again with the rest.
  ReceiveEvent feed(ByteView bytes, size_t* consumed);
  // Forgets a partial frame; the next byte starts a new one.
  void reset();

 private:
  CobsDecoder cobs_;
  size_t size_ = 0;          // decoded bytes in buffer_
  bool in_frame_ = false;    // bytes other than 0x00 since the last delimiter
  bool skipping_ = false;    // an overlong frame: ignore bytes up to the next 0x00
  uint8_t buffer_[kMaxMessageSize + kUartCrcSize] = {};
};

}  // namespace tetrapulse::protocol
