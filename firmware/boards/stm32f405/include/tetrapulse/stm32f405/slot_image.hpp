#pragma once
// The checks an image in a slot must pass before it is started (SPEC.md §7.3 step 4):
// its header decodes, it fits this board, it was linked for this slot with the vector
// table where this chip can point VTOR, it fits the slot, and its payload CRC matches.
#include <cstdint>

#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::stm32f405 {

// Board revision this firmware reports and checks images against.
constexpr uint8_t kHardwareRevision = 1;
// VTOR alignment on this chip (98 vectors -> 512 bytes).
constexpr uint32_t kVectorAlignment = 512;

// The header of the image at `slot_base` if the image passes every check; its error
// otherwise (kImageRejected for a mismatch with the board or the slot).
protocol::Result<protocol::ImageHeader> check_slot_image(uint32_t slot_base, uint32_t slot_size);

// The board-side rules of a decoded header for `slot_base` (everything but the CRCs).
protocol::Status check_header_for_slot(const protocol::ImageHeader& header, uint32_t slot_base,
                                       uint32_t slot_size);

}  // namespace tetrapulse::stm32f405
