#include "tetrapulse/protocol/image_header.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr uint16_t kHeaderSizeField = kImageHeaderSize;
constexpr size_t kReservedBegin = 36;
constexpr size_t kCrcOffset = 60;

}  // namespace

Status validate(const ImageHeader& h) {
  if (!is_known(h.hw_model)) return Error::kBadValue;
  if (h.hw_revision_min > h.hw_revision_max) return Error::kBadValue;
  if (h.payload_size == 0) return Error::kBadLength;
  if (h.vector_offset < kImageHeaderSize || h.vector_offset % kMinVectorAlignment != 0) return Error::kBadValue;
  if (h.load_address % kMinVectorAlignment != 0) return Error::kBadValue;
  if (image_size(h) > UINT32_MAX) return Error::kBadLength;  // the image must be addressable
  if (h.flags != 0) return Error::kBadValue;
  return {};
}

Status encode_image_header(const ImageHeader& h, ByteWriter& out) {
  if (const Status s = validate(h); !s.ok()) return s;
  uint8_t bytes[kImageHeaderSize] = {};
  ByteWriter w(bytes, sizeof(bytes));
  w.u32(kImageMagic);
  w.u16(kImageHeaderVersion);
  w.u16(kHeaderSizeField);
  w.u16(static_cast<uint16_t>(h.hw_model));
  w.u8(h.hw_revision_min);
  w.u8(h.hw_revision_max);
  w.u32(h.fw_version);
  w.u32(h.payload_size);
  w.u32(h.vector_offset);
  w.u32(h.load_address);
  w.u32(h.payload_crc32c);
  w.u32(h.flags);
  // bytes 36..59 stay zero (reserved)
  ByteWriter crc(bytes + kCrcOffset, 4);
  crc.u32(crc32c(bytes, kCrcOffset));
  out.bytes(bytes, sizeof(bytes));
  return out.ok() ? Status{} : Error::kBufferTooSmall;
}

Result<ImageHeader> decode_image_header(ByteView image) {
  if (image.size < kImageHeaderSize) return Error::kTruncated;
  ByteReader r(image.subview(0, kImageHeaderSize));
  if (r.u32() != kImageMagic) return Error::kBadValue;
  if (r.u16() != kImageHeaderVersion) return Error::kBadVersion;
  if (r.u16() != kHeaderSizeField) return Error::kBadLength;
  ImageHeader h;
  h.hw_model = static_cast<HwModel>(r.u16());
  h.hw_revision_min = r.u8();
  h.hw_revision_max = r.u8();
  h.fw_version = r.u32();
  h.payload_size = r.u32();
  h.vector_offset = r.u32();
  h.load_address = r.u32();
  h.payload_crc32c = r.u32();
  h.flags = r.u32();
  bool reserved_zero = true;
  for (size_t i = kReservedBegin; i < kCrcOffset; ++i) {
    if (r.u8() != 0) reserved_zero = false;
  }
  const uint32_t header_crc = r.u32();
  if (header_crc != crc32c(image.data, kCrcOffset)) return Error::kBadCrc;
  if (!reserved_zero) return Error::kBadValue;
  if (const Status s = validate(h); !s.ok()) return s.error();
  return h;
}

Status fits(const ImageHeader& h, HwModel hw_model, uint8_t hw_revision) {
  if (h.hw_model != hw_model) return Error::kImageRejected;
  if (hw_revision < h.hw_revision_min || hw_revision > h.hw_revision_max) return Error::kImageRejected;
  return {};
}

Status check_payload(const ImageHeader& h, ByteView image) {
  if (image.size != image_size(h)) return Error::kImageRejected;
  const ByteView payload = image.subview(h.vector_offset, h.payload_size);
  if (crc32c(payload.data, payload.size) != h.payload_crc32c) return Error::kImageRejected;
  return {};
}

}  // namespace tetrapulse::protocol
