#pragma once
// How the fuzz targets read structured input from bytes, and how the seed generator
// writes the golden vectors in the same form.
//
// CAN frame stream: records of [head u8][id u32 LE][data], where head bits 0..3 are
// the frame's size (0..15; 9..15 are invalid sizes the receiver must refuse, and
// carry 8 data bytes) and bits 4..7 the time since the previous frame, in steps of
// kCanFuzzTimeStepNs.
// USB packet stream: records of [size u8][packet], the size taken modulo 66 so that
// 65 (one byte over a full-speed packet) also occurs.
// USB control stream (MESSAGE_OUT): records as the packet stream, except that a record
// whose first byte is kUsbSetupRecord is a setup stage: wLength u16 LE follows.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tetrapulse/protocol/can_frame.hpp"

namespace tetrapulse::protocol::fuzz {

constexpr int64_t kCanFuzzTimeStepNs = 10'000'000;  // 10 ms; the fuzzed receiver times out after 100 ms

// Reads the next CAN record at `*pos`; false when the input has no complete record left.
inline bool next_can_frame(const uint8_t* data, size_t size, size_t* pos, CanFrame* frame, int64_t* dt_ns) {
  if (size - *pos < 5) return false;
  const uint8_t head = data[*pos];
  const size_t length = (head & 0x0F) > kCanFrameDataSize ? kCanFrameDataSize : (head & 0x0F);
  if (size - *pos < 5 + length) return false;
  frame->id = static_cast<uint32_t>(data[*pos + 1]) | (static_cast<uint32_t>(data[*pos + 2]) << 8) |
              (static_cast<uint32_t>(data[*pos + 3]) << 16) | (static_cast<uint32_t>(data[*pos + 4]) << 24);
  frame->size = static_cast<uint8_t>(head & 0x0F);
  for (size_t i = 0; i < kCanFrameDataSize; ++i) frame->data[i] = i < length ? data[*pos + 5 + i] : 0;
  *dt_ns = static_cast<int64_t>(head >> 4) * kCanFuzzTimeStepNs;
  *pos += 5 + length;
  return true;
}

inline void append_can_frame(const CanFrame& frame, uint8_t time_steps, std::vector<uint8_t>* out) {
  out->push_back(static_cast<uint8_t>((time_steps << 4) | (frame.size & 0x0F)));
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<uint8_t>(frame.id >> (8 * i)));
  for (size_t i = 0; i < frame.size && i < kCanFrameDataSize; ++i) out->push_back(frame.data[i]);
}

// Reads the next USB packet at `*pos` into `*packet`/`*length`; false at the end.
inline bool next_usb_packet(const uint8_t* data, size_t size, size_t* pos, const uint8_t** packet,
                            size_t* length) {
  if (*pos >= size) return false;
  const size_t wanted = data[*pos] % 66;
  const size_t available = size - *pos - 1;
  *length = wanted < available ? wanted : available;
  *packet = data + *pos + 1;
  *pos += 1 + *length;
  return true;
}

inline void append_usb_packet(const uint8_t* packet, size_t length, std::vector<uint8_t>* out) {
  out->push_back(static_cast<uint8_t>(length));
  out->insert(out->end(), packet, packet + length);
}

constexpr uint8_t kUsbSetupRecord = 0xFF;

struct UsbControlRecord {
  bool setup = false;
  uint16_t w_length = 0;            // setup
  const uint8_t* packet = nullptr;  // data-stage packet
  size_t length = 0;
};

// Reads the next USB control record at `*pos`; false at the end (or a setup cut short).
inline bool next_usb_control_record(const uint8_t* data, size_t size, size_t* pos, UsbControlRecord* r) {
  if (*pos >= size) return false;
  r->setup = data[*pos] == kUsbSetupRecord;
  if (!r->setup) return next_usb_packet(data, size, pos, &r->packet, &r->length);
  if (size - *pos < 3) return false;
  r->w_length = static_cast<uint16_t>(data[*pos + 1] | (data[*pos + 2] << 8));
  *pos += 3;
  return true;
}

inline void append_usb_setup(uint16_t w_length, std::vector<uint8_t>* out) {
  out->push_back(kUsbSetupRecord);
  out->push_back(static_cast<uint8_t>(w_length));
  out->push_back(static_cast<uint8_t>(w_length >> 8));
}

}  // namespace tetrapulse::protocol::fuzz
