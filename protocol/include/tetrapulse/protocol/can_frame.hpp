#pragma once
// Classic CAN frames and the tail byte that ends each one (SPEC.md §4.2).
//
// The last data byte of every frame is the tail byte:
//   bit 7 start of transfer, bit 6 end of transfer, bit 5 toggle, bits 4..0 transfer-id.
// A message of at most 7 bytes travels in one frame (start = end = toggle = 1, no CRC).
// A longer one is followed by its CRC-16/CCITT-FALSE, most significant byte first
// (so the CRC over message and CRC is 0), and cut into frames of 7 bytes plus tail;
// the last frame carries the 1..7 bytes that remain. Toggle is 1 in the first frame
// and alternates.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::protocol {

constexpr size_t kCanFrameDataSize = 8;
constexpr size_t kCanFramePayloadSize = kCanFrameDataSize - 1;  // bytes before the tail byte
constexpr size_t kCanTransferCrcSize = 2;
constexpr uint8_t kCanTransferIdModulo = 32;
// Largest message that goes in one frame; a longer one is a multi-frame transfer.
constexpr size_t kCanSingleFrameMaxMessage = kCanFramePayloadSize;
// Most frames one transfer can take (a kMaxMessageSize message).
constexpr size_t kCanMaxFramesPerTransfer =
    (kMaxMessageSize + kCanTransferCrcSize + kCanFramePayloadSize - 1) / kCanFramePayloadSize;

// One classic CAN data frame with a 29-bit extended identifier.
struct CanFrame {
  uint32_t id = 0;                      // 29-bit identifier (no flag bits)
  uint8_t size = 0;                     // data length 0..8
  uint8_t data[kCanFrameDataSize] = {};
};

struct CanTail {
  bool start = false;
  bool end = false;
  bool toggle = false;
  uint8_t transfer_id = 0;  // 0..31

  bool operator==(const CanTail& o) const {
    return start == o.start && end == o.end && toggle == o.toggle && transfer_id == o.transfer_id;
  }
};

constexpr uint8_t encode_can_tail(const CanTail& t) {
  return static_cast<uint8_t>((t.start ? 0x80 : 0) | (t.end ? 0x40 : 0) | (t.toggle ? 0x20 : 0) |
                              (t.transfer_id & 0x1F));
}

constexpr CanTail decode_can_tail(uint8_t b) {
  return CanTail{(b & 0x80) != 0, (b & 0x40) != 0, (b & 0x20) != 0,
                 static_cast<uint8_t>(b & 0x1F)};
}

// Frames needed for a message of `message_size` bytes (3..kMaxMessageSize).
constexpr size_t can_frame_count(size_t message_size) {
  if (message_size <= kCanSingleFrameMaxMessage) return 1;
  return (message_size + kCanTransferCrcSize + kCanFramePayloadSize - 1) / kCanFramePayloadSize;
}

}  // namespace tetrapulse::protocol
