#pragma once
// Firmware images for tests (protocol/SPEC.md §7): a valid header and seeded payload bytes.
#include <cstdint>
#include <vector>

#include "tetrapulse/protocol/hw_model.hpp"

namespace tetrapulse::host::testing {

struct TestImageSpec {
  protocol::HwModel hw_model = protocol::HwModel::kLinuxBoard;
  uint8_t hw_revision_min = 0;
  uint8_t hw_revision_max = 255;
  uint32_t fw_version = 0x01020003;  // 1.2.3
  uint32_t load_address = 0;
  uint32_t vector_offset = 128;
  uint32_t payload_size = 3000;
  uint32_t seed = 1;
};

std::vector<uint8_t> make_test_image(const TestImageSpec& spec);

}  // namespace tetrapulse::host::testing
