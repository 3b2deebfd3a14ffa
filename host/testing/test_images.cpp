#include "test_images.hpp"

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"

namespace tetrapulse::host::testing {

std::vector<uint8_t> make_test_image(const TestImageSpec& spec) {
  std::vector<uint8_t> image(spec.vector_offset + spec.payload_size, 0xFF);
  uint32_t x = spec.seed * 2654435761u + 1;
  for (uint32_t i = spec.vector_offset; i < image.size(); ++i) {
    x = x * 1664525u + 1013904223u;  // any bytes will do; a zero in them tests the framings
    image[i] = static_cast<uint8_t>(x >> 24);
  }
  protocol::ImageHeader h;
  h.hw_model = spec.hw_model;
  h.hw_revision_min = spec.hw_revision_min;
  h.hw_revision_max = spec.hw_revision_max;
  h.fw_version = spec.fw_version;
  h.payload_size = spec.payload_size;
  h.vector_offset = spec.vector_offset;
  h.load_address = spec.load_address;
  h.payload_crc32c = protocol::crc32c(image.data() + spec.vector_offset, spec.payload_size);
  protocol::ByteWriter w(image.data(), protocol::kImageHeaderSize);
  if (!protocol::encode_image_header(h, w)) image.clear();
  return image;
}

}  // namespace tetrapulse::host::testing
