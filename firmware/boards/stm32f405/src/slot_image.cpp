#include "tetrapulse/stm32f405/slot_image.hpp"

namespace tetrapulse::stm32f405 {

namespace tp = protocol;

tp::Status check_header_for_slot(const tp::ImageHeader& h, uint32_t slot_base, uint32_t slot_size) {
  if (const tp::Status s = tp::fits(h, tp::HwModel::kStm32f405Reference, kHardwareRevision); !s) return s;
  if (h.load_address != slot_base) return tp::Error::kImageRejected;
  if (h.vector_offset % kVectorAlignment != 0) return tp::Error::kImageRejected;
  if (tp::image_size(h) > slot_size) return tp::Error::kImageRejected;
  return {};
}

tp::Result<tp::ImageHeader> check_slot_image(uint32_t slot_base, uint32_t slot_size) {
  // Flash is memory-mapped: the slot is read in place.
  const uint8_t* slot = reinterpret_cast<const uint8_t*>(slot_base);
  const tp::Result<tp::ImageHeader> h = tp::decode_image_header(tp::ByteView{slot, slot_size});
  if (!h) return h.error();
  if (const tp::Status s = check_header_for_slot(*h, slot_base, slot_size); !s) return s.error();
  const tp::ByteView image{slot, static_cast<size_t>(tp::image_size(*h))};
  if (const tp::Status s = tp::check_payload(*h, image); !s) return s.error();
  return *h;
}

}  // namespace tetrapulse::stm32f405
