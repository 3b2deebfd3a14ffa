#pragma once
// Cuts a message into the CAN frames of one transfer (SPEC.md §4.2–4.3).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/can_id.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// Everything about a transfer except the message; the identifier's type field is
// taken from the message's type byte (message[1]).
struct CanTransferHeader {
  uint8_t priority = kCanPriorityRequest;
  uint8_t destination = kCanBroadcastNode;
  uint8_t source = kCanHostNode;
  uint8_t transfer_id = 0;  // 0..31
};

// kBadLength unless 3 <= message.size <= kMaxMessageSize; kBadValue for a priority
// above 7, source 255 or transfer-id above 31.
Status check_can_transfer(const CanTransferHeader& header, ByteView message);

// Frame `index` (0 .. can_frame_count(message.size) - 1) of the transfer, built on
// demand so that a driver with few transmit mailboxes needs no frame array.
// Errors as check_can_transfer, and kBadValue for an index past the last frame.
Result<CanFrame> make_can_transfer_frame(const CanTransferHeader& header, ByteView message,
                                         size_t index);

// A node's sending side: keeps the transfer-id counter of each (type, destination)
// it sends to and segments messages. The counters live in a small table; when it is
// full the least recently used one is reused and restarts at 0, which is harmless
// because receivers use transfer-ids only to tell consecutive transfers apart
// (SPEC.md §4.4).
//
// Frames of one transfer must reach the bus in order, and a transfer must end before
// the next one with the same identifier starts (one transmit FIFO, or bxCAN TXFP=1).
class CanTransferSender {
 public:
  static constexpr size_t kCounterSlots = 16;

  // `first_transfer_id`: where every (type, destination) counter starts. A host process
  // picks it at random: a receiver takes a single-frame transfer with the tail byte of the
  // session's previous one for a repeat, so a new process starting where the last one did
  // would have its first request ignored if it came within the transfer timeout.
  explicit CanTransferSender(uint8_t source_node, uint8_t first_transfer_id = 0)
      : source_(source_node), first_transfer_id_(static_cast<uint8_t>(first_transfer_id % kCanTransferIdModulo)) {}

  uint8_t source() const { return source_; }

  // The transfer-id for the next transfer of `type` to `destination`; advances it.
  uint8_t next_transfer_id(uint8_t type, uint8_t destination);

  // Writes the frames of one transfer into `frames`; returns how many.
  // kBufferTooSmall (and no transfer-id used) when `capacity` is short.
  Result<size_t> segment(uint8_t priority, uint8_t destination, ByteView message,
                         CanFrame* frames, size_t capacity);

  // Hands each frame of one transfer to `sink` (callable as Status(const CanFrame&)),
  // stopping at the first error the sink returns.
  template <typename Sink>
  Status send(uint8_t priority, uint8_t destination, ByteView message, Sink&& sink) {
    CanTransferHeader header{priority, destination, source_, 0};
    const Status valid = check_can_transfer(header, message);
    if (!valid) return valid;
    header.transfer_id = next_transfer_id(message[1], destination);
    const size_t count = can_frame_count(message.size);
    for (size_t i = 0; i < count; ++i) {
      const Result<CanFrame> frame = make_can_transfer_frame(header, message, i);
      if (!frame) return frame.error();
      const Status sent = sink(*frame);
      if (!sent) return sent;
    }
    return Status{};
  }

 private:
  struct CounterSlot {
    uint8_t type = 0;
    uint8_t destination = 0;
    uint8_t next_transfer_id = 0;
    bool used = false;
    uint32_t last_use = 0;
  };

  uint8_t source_;
  uint8_t first_transfer_id_ = 0;
  uint32_t clock_ = 0;
  CounterSlot slots_[kCounterSlots];
};

}  // namespace tetrapulse::protocol
