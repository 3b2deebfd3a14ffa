#pragma once
// 29-bit extended CAN identifiers of the tetrapulse CAN transport (SPEC.md §4.1).
//
//   bits 28..26  priority     (0 highest)
//   bits 25..24  reserved     (0; frames with either bit set are not ours)
//   bits 23..16  message type (equal to the message's `type` byte)
//   bits 15..8   destination  (node id, 0xFF = broadcast)
//   bits  7..0   source       (0 = host / sync master, 1..254 boards, 255 invalid)
#include <cstdint>

#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// Priorities (lower wins arbitration).
constexpr uint8_t kCanPrioritySync = 0;      // Sync and FollowUp: their latency is the clock error
constexpr uint8_t kCanPriorityRequest = 4;
constexpr uint8_t kCanPriorityResponse = 4;
constexpr uint8_t kCanPriorityBulk = 6;      // firmware update chunks
constexpr uint8_t kCanPriorityLowest = 7;

// Node ids.
constexpr uint8_t kCanHostNode = 0;          // the host, which is also the sync master
constexpr uint8_t kCanFirstBoardNode = 1;
constexpr uint8_t kCanLastBoardNode = 254;
constexpr uint8_t kCanBroadcastNode = 0xFF;  // as destination: every node; never a source

constexpr uint32_t kCanExtendedIdMask = 0x1FFFFFFFu;
constexpr uint32_t kCanReservedBits = 0x03000000u;

struct CanId {
  uint8_t priority = kCanPriorityRequest;  // 0..7
  uint8_t type = 0;
  uint8_t destination = kCanBroadcastNode;
  uint8_t source = kCanHostNode;           // 0..254

  bool operator==(const CanId& o) const {
    return priority == o.priority && type == o.type && destination == o.destination &&
           source == o.source;
  }
  bool operator!=(const CanId& o) const { return !(*this == o); }
};

// kBadValue when priority > 7 or source == 255.
Result<uint32_t> pack_can_id(const CanId& id);
// kBadValue when the value exceeds 29 bits, a reserved bit is set or the source is 255.
Result<CanId> unpack_can_id(uint32_t raw);

// An acceptance filter: a 29-bit identifier matches when (raw & mask) == (id & mask).
// On SocketCAN add CAN_EFF_FLAG to both id and mask (and to the frame's id) so that
// standard frames never match; on bxCAN use 32-bit mask mode with IDE set.
struct CanFilter {
  uint32_t id = 0;
  uint32_t mask = 0;
};
constexpr bool can_filter_matches(const CanFilter& f, uint32_t raw) {
  return (raw & f.mask) == (f.id & f.mask);
}

// What a node must receive: frames addressed to it and broadcasts (two filters,
// each also requiring the reserved bits to be 0). For the host pass kCanHostNode.
struct CanNodeFilters {
  CanFilter addressed;
  CanFilter broadcast;
};
CanNodeFilters can_node_filters(uint8_t node);

}  // namespace tetrapulse::protocol
