#include "tetrapulse/protocol/can_transfer_sender.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {

Status check_can_transfer(const CanTransferHeader& header, ByteView message) {
  if (message.size < 3 || message.size > kMaxMessageSize) return Error::kBadLength;
  if (header.priority > kCanPriorityLowest || header.source == kCanBroadcastNode ||
      header.transfer_id >= kCanTransferIdModulo) {
    return Error::kBadValue;
  }
  return Status{};
}

Result<CanFrame> make_can_transfer_frame(const CanTransferHeader& header, ByteView message,
                                         size_t index) {
  const Status valid = check_can_transfer(header, message);
  if (!valid) return valid.error();
  const size_t frames = can_frame_count(message.size);
  if (index >= frames) return Error::kBadValue;

  const Result<uint32_t> id =
      pack_can_id(CanId{header.priority, message[1], header.destination, header.source});
  if (!id) return id.error();
  CanFrame frame;
  frame.id = *id;

  const CanTail tail{index == 0, index + 1 == frames, index % 2 == 0, header.transfer_id};
  if (frames == 1) {
    for (size_t i = 0; i < message.size; ++i) frame.data[i] = message[i];
    frame.data[message.size] = encode_can_tail(tail);
    frame.size = static_cast<uint8_t>(message.size + 1);
    return frame;
  }

  // Multi-frame: the payload is the message followed by its CRC, high byte first.
  const size_t payload = message.size + kCanTransferCrcSize;
  const size_t offset = index * kCanFramePayloadSize;
  const size_t count = payload - offset < kCanFramePayloadSize ? payload - offset : kCanFramePayloadSize;
  uint16_t crc = 0;
  if (offset + count > message.size) crc = crc16_ccitt(message.data, message.size);
  for (size_t i = 0; i < count; ++i) {
    const size_t pos = offset + i;
    if (pos < message.size) {
      frame.data[i] = message[pos];
    } else {
      frame.data[i] = static_cast<uint8_t>(pos == message.size ? crc >> 8 : crc);
    }
  }
  frame.data[count] = encode_can_tail(tail);
  frame.size = static_cast<uint8_t>(count + 1);
  return frame;
}

uint8_t CanTransferSender::next_transfer_id(uint8_t type, uint8_t destination) {
  ++clock_;
  CounterSlot* slot = nullptr;
  for (CounterSlot& s : slots_) {
    if (s.used && s.type == type && s.destination == destination) {
      slot = &s;
      break;
    }
  }
  if (slot == nullptr) {
    // Take an unused slot, else the least recently used one.
    slot = &slots_[0];
    for (CounterSlot& s : slots_) {
      if (!s.used) {
        slot = &s;
        break;
      }
      if (s.last_use < slot->last_use) slot = &s;
    }
    *slot = CounterSlot{type, destination, first_transfer_id_, true, 0};
  }
  slot->last_use = clock_;
  const uint8_t id = slot->next_transfer_id;
  slot->next_transfer_id = static_cast<uint8_t>((id + 1) % kCanTransferIdModulo);
  return id;
}

Result<size_t> CanTransferSender::segment(uint8_t priority, uint8_t destination, ByteView message,
                                          CanFrame* frames, size_t capacity) {
  CanTransferHeader header{priority, destination, source_, 0};
  const Status valid = check_can_transfer(header, message);
  if (!valid) return valid.error();
  const size_t count = can_frame_count(message.size);
  if (count > capacity) return Error::kBufferTooSmall;
  size_t written = 0;
  const Status sent = send(priority, destination, message, [&](const CanFrame& f) {
    frames[written++] = f;
    return Status{};
  });
  if (!sent) return sent.error();
  return written;
}

}  // namespace tetrapulse::protocol
