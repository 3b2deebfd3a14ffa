#pragma once
// Firmware images for the simulated board (SPEC.md §7): a valid header for hw_model 3
// (simulated), load_address 0 (the simulated board runs the same code from either slot),
// and a payload of seeded bytes standing in for code.
#include <cstdint>
#include <vector>

#include "tetrapulse/protocol/hw_model.hpp"

namespace tetrapulse::sim_board {

struct SimImageSpec {
  uint32_t fw_version = 0x01000000;  // pack_version(1, 0, 0)
  uint32_t payload_size = 1024;
  uint32_t vector_offset = 128;
  uint8_t hw_revision_min = 0;
  uint8_t hw_revision_max = 255;
  uint32_t seed = 1;
  protocol::HwModel hw_model = protocol::HwModel::kSimulatedBoard;  // another: a foreign image
};

std::vector<uint8_t> make_sim_image(const SimImageSpec& spec);

}  // namespace tetrapulse::sim_board
