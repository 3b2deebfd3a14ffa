#include "tetrapulse/protocol/can_id.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr uint32_t kPriorityShift = 26;
constexpr uint32_t kTypeShift = 16;
constexpr uint32_t kDestinationShift = 8;
constexpr uint32_t kDestinationMask = 0xFFu << kDestinationShift;

}  // namespace

Result<uint32_t> pack_can_id(const CanId& id) {
  if (id.priority > kCanPriorityLowest || id.source == kCanBroadcastNode) return Error::kBadValue;
  return (static_cast<uint32_t>(id.priority) << kPriorityShift) |
         (static_cast<uint32_t>(id.type) << kTypeShift) |
         (static_cast<uint32_t>(id.destination) << kDestinationShift) | id.source;
}

Result<CanId> unpack_can_id(uint32_t raw) {
  if ((raw & ~kCanExtendedIdMask) != 0 || (raw & kCanReservedBits) != 0) return Error::kBadValue;
  CanId id;
  id.priority = static_cast<uint8_t>(raw >> kPriorityShift);
  id.type = static_cast<uint8_t>(raw >> kTypeShift);
  id.destination = static_cast<uint8_t>(raw >> kDestinationShift);
  id.source = static_cast<uint8_t>(raw);
  if (id.source == kCanBroadcastNode) return Error::kBadValue;
  return id;
}

CanNodeFilters can_node_filters(uint8_t node) {
  const uint32_t mask = kDestinationMask | kCanReservedBits;
  return CanNodeFilters{CanFilter{static_cast<uint32_t>(node) << kDestinationShift, mask},
                        CanFilter{static_cast<uint32_t>(kCanBroadcastNode) << kDestinationShift, mask}};
}

}  // namespace tetrapulse::protocol
