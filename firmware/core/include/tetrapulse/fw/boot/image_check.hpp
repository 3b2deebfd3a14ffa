#pragma once
// The checks an image in a slot must pass before it is started or marked pending
// (SPEC.md §7.3 step 3 and 4): the header decodes, fits the board, carries the slot's
// load address and an aligned vector table, and the payload CRC-32C matches.
#include <cstdint>

#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/hw_model.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

struct BoardModel {
  protocol::HwModel model = protocol::HwModel::kSimulatedBoard;
  uint8_t revision = 0;
};

// CRC-32C of `size` flash bytes at `address`.
protocol::Result<uint32_t> flash_crc32c(const Flash& flash, uint32_t address, uint32_t size);

// The header of the image in `slot` when every check passes; kImageRejected (or the
// header's decode error, or kFlashError) otherwise. `image_size`, when non-zero, must
// equal vector_offset + payload_size.
protocol::Result<protocol::ImageHeader> check_slot_image(const Flash& flash, const SlotLayout& slot,
                                                         const BoardModel& board, uint32_t vector_alignment,
                                                         uint32_t image_size = 0);

}  // namespace tetrapulse::fw
