#include "tetrapulse/fw/boot/image_check.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::fw {

protocol::Result<uint32_t> flash_crc32c(const Flash& flash, uint32_t address, uint32_t size) {
  protocol::Crc32c crc;
  uint8_t buf[64];
  for (uint32_t done = 0; done < size;) {
    const uint32_t n = size - done < sizeof(buf) ? size - done : static_cast<uint32_t>(sizeof(buf));
    if (!flash.read(address + done, buf, n)) return protocol::Error::kFlashError;
    crc.update(buf, n);
    done += n;
  }
  return crc.value();
}

protocol::Result<protocol::ImageHeader> check_slot_image(const Flash& flash, const SlotLayout& slot,
                                                         const BoardModel& board, uint32_t vector_alignment,
                                                         uint32_t image_size) {
  uint8_t bytes[protocol::kImageHeaderSize];
  if (slot.region.size < sizeof(bytes)) return protocol::Error::kImageRejected;
  if (!flash.read(slot.region.address, bytes, sizeof(bytes))) return protocol::Error::kFlashError;
  const protocol::Result<protocol::ImageHeader> header =
      protocol::decode_image_header(protocol::ByteView{bytes, sizeof(bytes)});
  if (!header) return header.error();
  const protocol::ImageHeader& h = *header;
  if (!protocol::fits(h, board.model, board.revision)) return protocol::Error::kImageRejected;
  if (h.load_address != slot.load_address) return protocol::Error::kImageRejected;
  if (vector_alignment == 0 || h.vector_offset % vector_alignment != 0) return protocol::Error::kImageRejected;
  const uint64_t size = protocol::image_size(h);
  if (size > slot.region.size) return protocol::Error::kImageRejected;
  if (image_size != 0 && size != image_size) return protocol::Error::kImageRejected;
  const protocol::Result<uint32_t> crc = flash_crc32c(flash, slot.region.address + h.vector_offset, h.payload_size);
  if (!crc) return crc.error();
  if (*crc != h.payload_crc32c) return protocol::Error::kImageRejected;
  return h;
}

}  // namespace tetrapulse::fw
