#pragma once
// The 64-byte header at the start of every firmware image (SPEC.md §7). A board refuses an
// image whose header does not decode, does not fit it, or whose payload CRC is wrong.
//
//   image = [header, 64 bytes][padding up to vector_offset][payload, payload_size bytes]
//
// Addresses are byte addresses in the board's memory map; sizes are bytes.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/hw_model.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

constexpr size_t kImageHeaderSize = 64;
constexpr uint32_t kImageMagic = 0x57465054;  // bytes "TPFW" read as a little-endian u32
constexpr uint16_t kImageHeaderVersion = 1;
// Cortex-M VTOR needs at least 128-byte alignment (more with many interrupts: a board
// checks its own stricter rule, e.g. 512 bytes on the STM32F405).
constexpr uint32_t kMinVectorAlignment = 128;

// The header's variable fields; magic, header_version, header_size, the reserved bytes
// and header_crc32c are written by encode and checked by decode.
struct ImageHeader {
  HwModel hw_model = HwModel::kStm32f405Reference;
  uint8_t hw_revision_min = 0;  // the image runs on revisions min..max inclusive
  uint8_t hw_revision_max = 0;
  uint32_t fw_version = 0;      // pack_version()
  uint32_t payload_size = 0;    // bytes from vector_offset to the end of the image, > 0
  uint32_t vector_offset = 0;   // where the vector table starts; >= 64, multiple of kMinVectorAlignment
  uint32_t load_address = 0;    // slot base the image was linked for; multiple of kMinVectorAlignment
  uint32_t payload_crc32c = 0;  // CRC-32C of the payload bytes
  uint32_t flags = 0;           // none defined in header version 1: must be 0
};

// Whole image length: vector_offset + payload_size.
constexpr uint64_t image_size(const ImageHeader& h) {
  return static_cast<uint64_t>(h.vector_offset) + h.payload_size;
}

// kBadValue / kBadLength when a field is outside its range (SPEC.md §7).
Status validate(const ImageHeader& header);

// Validates, then appends the 64 header bytes, header_crc32c included.
Status encode_image_header(const ImageHeader& header, ByteWriter& out);

// Decodes the header at the start of `image` (bytes after the first 64 are not read).
// kTruncated (< 64 bytes), kBadValue (magic), kBadVersion (header_version), kBadLength
// (header_size), kBadCrc (header_crc32c), then validate()'s errors.
Result<ImageHeader> decode_image_header(ByteView image);

// kImageRejected unless the image is built for this board model and revision.
Status fits(const ImageHeader& header, HwModel hw_model, uint8_t hw_revision);

// kImageRejected unless `image` holds exactly image_size(header) bytes and the payload's
// CRC-32C equals payload_crc32c.
Status check_payload(const ImageHeader& header, ByteView image);

}  // namespace tetrapulse::protocol
