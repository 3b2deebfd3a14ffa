#include "tetrapulse/linux_board/board_image.hpp"

#include <algorithm>
#include <cstdio>

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::linux_board {

namespace tp = protocol;

std::vector<uint8_t> make_linux_image(uint32_t fw_version, const std::vector<uint8_t>& payload) {
  constexpr uint32_t kVectorOffset = tp::kMinVectorAlignment;
  if (payload.empty()) return {};  // a header needs a payload
  std::vector<uint8_t> image(kVectorOffset + payload.size(), 0x00);
  std::copy(payload.begin(), payload.end(), image.begin() + kVectorOffset);
  tp::ImageHeader h;
  h.hw_model = tp::HwModel::kLinuxBoard;
  h.hw_revision_min = 0;
  h.hw_revision_max = 255;
  h.fw_version = fw_version;
  h.payload_size = static_cast<uint32_t>(payload.size());
  h.vector_offset = kVectorOffset;
  h.load_address = 0;
  h.payload_crc32c = tp::crc32c(payload.data(), payload.size());
  tp::ByteWriter out(image.data(), tp::kImageHeaderSize);
  if (!tp::encode_image_header(h, out)) image.clear();
  return image;
}

std::vector<uint8_t> seeded_payload(size_t count, uint32_t seed) {
  std::vector<uint8_t> bytes(count);
  uint32_t x = seed * 2654435761u + 1;
  for (uint8_t& b : bytes) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    b = static_cast<uint8_t>(x);
  }
  return bytes;
}

std::optional<uint32_t> parse_version(const std::string& text) {
  unsigned major = 0;
  unsigned minor = 0;
  unsigned patch = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%u.%u.%u%c", &major, &minor, &patch, &tail) != 3) return std::nullopt;
  if (major > 255 || minor > 255 || patch > 65535) return std::nullopt;
  return tp::pack_version(static_cast<uint8_t>(major), static_cast<uint8_t>(minor), static_cast<uint16_t>(patch));
}

}  // namespace tetrapulse::linux_board
