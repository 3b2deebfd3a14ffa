#include "tetrapulse/sim_board/sim_image.hpp"

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"

namespace tetrapulse::sim_board {

std::vector<uint8_t> make_sim_image(const SimImageSpec& spec) {
  std::vector<uint8_t> image(spec.vector_offset + spec.payload_size, 0x00);
  uint32_t x = spec.seed * 2654435761u + 1;
  for (uint32_t i = 0; i < spec.payload_size; ++i) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    image[spec.vector_offset + i] = static_cast<uint8_t>(x);
  }
  protocol::ImageHeader h;
  h.hw_model = spec.hw_model;
  h.hw_revision_min = spec.hw_revision_min;
  h.hw_revision_max = spec.hw_revision_max;
  h.fw_version = spec.fw_version;
  h.payload_size = spec.payload_size;
  h.vector_offset = spec.vector_offset;
  h.load_address = 0;
  h.payload_crc32c = protocol::crc32c(image.data() + spec.vector_offset, spec.payload_size);
  protocol::ByteWriter out(image.data(), protocol::kImageHeaderSize);
  if (!protocol::encode_image_header(h, out)) image.clear();  // an invalid spec gives no image
  return image;
}

}  // namespace tetrapulse::sim_board
