#pragma once
// Sizes every implementation of the protocol agrees on (SPEC.md).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/code.hpp"  // kMaxCodeLength

namespace tetrapulse::protocol {

constexpr uint8_t kProtocolVersion = 1;
// Largest encoded message (header + body) any transport must carry.
constexpr size_t kMaxMessageSize = 320;
// Largest firmware-update chunk payload.
constexpr size_t kMaxUpdateChunk = 256;
// Markers per target.
constexpr size_t kMarkersPerTarget = 4;

}  // namespace tetrapulse::protocol
