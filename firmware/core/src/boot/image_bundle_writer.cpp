#include "tetrapulse/fw/boot/image_bundle_writer.hpp"

#include "tetrapulse/fw/boot/update_slot.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;
using tp::DfuStatusCode;

ImageBundleWriter::ImageBundleWriter(Flash& flash, const FlashLayout& layout, RecordStore& store,
                                     const BoardModel& board, uint8_t target, uint8_t fallback)
    : flash_(flash), layout_(layout), store_(store), board_(board), target_(target), fallback_(fallback) {}

void ImageBundleWriter::restart() {
  position_ = image_start_ = image_size_ = 0;
  keep_ = false;
  header_fill_ = 0;
  found_ = false;
  kept_ = tp::ImageHeader{};
}

void ImageBundleWriter::do_abort() { restart(); }  // the slot is left as it is: not pending, never started

DfuStatusCode ImageBundleWriter::program(uint32_t image_offset, const uint8_t* data, size_t size) {
  const uint32_t address = layout_.slots[target_].region.address + image_offset;
  return flash_.program(address, tp::ByteView{data, size}) ? DfuStatusCode::kOk : DfuStatusCode::kErrProg;
}

DfuStatusCode ImageBundleWriter::take_header() {
  const tp::Result<tp::ImageHeader> h = tp::decode_image_header(tp::ByteView{header_, sizeof(header_)});
  if (!h) return DfuStatusCode::kErrFile;
  const uint64_t size = tp::image_size(*h);  // > 64: vector_offset >= 64 and payload_size >= 1
  if (size > UINT32_MAX) return DfuStatusCode::kErrFile;
  image_size_ = static_cast<uint32_t>(size);
  const SlotLayout& slot = layout_.slots[target_];
  keep_ = h->load_address == slot.load_address;
  if (!keep_) return DfuStatusCode::kOk;
  if (found_) return DfuStatusCode::kErrFile;  // two images for one slot
  if (!tp::fits(*h, board_.model, board_.revision)) return DfuStatusCode::kErrTarget;
  if (size > slot.region.size) return DfuStatusCode::kErrAddress;
  found_ = true;
  kept_ = *h;
  return program(0, header_, sizeof(header_));
}

DfuStatusCode ImageBundleWriter::do_download(uint32_t offset, tp::ByteView block) {
  if (target_ >= kSlotCount) return DfuStatusCode::kErrTarget;
  if (offset == 0) {
    restart();
    if (!clear_pending_slot(store_, target_)) return DfuStatusCode::kErrWrite;
    if (!erase_slot(flash_, layout_.slots[target_])) return DfuStatusCode::kErrErase;
  }
  if (offset != position_) return DfuStatusCode::kErrAddress;
  size_t i = 0;
  while (i < block.size) {
    const size_t left = block.size - i;
    if (image_size_ == 0) {  // inside a header
      const size_t n = sizeof(header_) - header_fill_ < left ? sizeof(header_) - header_fill_ : left;
      for (size_t k = 0; k < n; ++k) header_[header_fill_ + k] = block[i + k];
      header_fill_ += n;
      i += n;
      position_ += static_cast<uint32_t>(n);
      if (header_fill_ == sizeof(header_)) {
        const DfuStatusCode s = take_header();
        if (s != DfuStatusCode::kOk) return s;
      }
      continue;
    }
    const uint32_t image_offset = position_ - image_start_;
    const uint32_t rest = image_size_ - image_offset;
    const size_t n = rest < left ? rest : left;
    if (keep_) {
      const DfuStatusCode s = program(image_offset, block.data + i, n);
      if (s != DfuStatusCode::kOk) return s;
    }
    i += n;
    position_ += static_cast<uint32_t>(n);
    if (position_ - image_start_ == image_size_) {  // the next image starts here
      image_start_ = position_;
      image_size_ = 0;
      header_fill_ = 0;
      keep_ = false;
    }
  }
  return DfuStatusCode::kOk;
}

uint32_t ImageBundleWriter::do_download_poll_ms(uint32_t offset, size_t size) const {
  const uint32_t program_ms = static_cast<uint32_t>((size * kProgramMsPerKiB + 1023) / 1024) + 1;
  return offset == 0 ? kEraseMs + program_ms : program_ms;
}

DfuStatusCode ImageBundleWriter::do_manifest(uint32_t size) {
  if (size != position_ || image_size_ != 0 || header_fill_ != 0) return DfuStatusCode::kErrNotDone;
  if (!found_) return DfuStatusCode::kErrFile;  // no image for the target slot
  const SlotLayout& slot = layout_.slots[target_];
  const tp::Result<tp::ImageHeader> checked =
      check_slot_image(flash_, slot, board_, layout_.vector_alignment, static_cast<uint32_t>(tp::image_size(kept_)));
  if (!checked) return DfuStatusCode::kErrVerify;
  if (!mark_slot_pending(store_, target_, kept_.fw_version, fallback_)) return DfuStatusCode::kErrWrite;
  return DfuStatusCode::kOk;
}

}  // namespace tetrapulse::fw
