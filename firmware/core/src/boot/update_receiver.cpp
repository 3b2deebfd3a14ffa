#include "tetrapulse/fw/boot/update_receiver.hpp"

#include "tetrapulse/fw/boot/update_slot.hpp"

namespace tetrapulse::fw {

using protocol::Error;
using protocol::UpdateState;

UpdateReceiver::UpdateReceiver(Flash& flash, const FlashLayout& layout, RecordStore& store, const BoardModel& board,
                               uint8_t active_slot)
    : flash_(flash),
      layout_(layout),
      store_(store),
      board_(board),
      target_(active_slot == 0 ? 1 : 0) {}

void UpdateReceiver::flash_failed() {
  if (flash_errors_ != UINT16_MAX) ++flash_errors_;
  state_ = UpdateState::kFailed;
}

protocol::Result<uint32_t> UpdateReceiver::begin(const protocol::UpdateBegin& request) {
  const SlotLayout& slot = layout_.slots[target_];
  if (request.image_size > slot.region.size) return Error::kImageRejected;
  state_ = UpdateState::kIdle;
  if (!clear_pending_slot(store_, target_) || !erase_slot(flash_, slot)) {
    flash_failed();
    return Error::kFlashError;
  }
  begin_ = request;
  next_offset_ = 0;
  have_last_ = false;
  state_ = UpdateState::kReceiving;
  return uint32_t{0};
}

protocol::Result<uint32_t> UpdateReceiver::chunk(const protocol::UpdateChunk& request, uint16_t* detail) {
  *detail = static_cast<uint16_t>(next_offset_);
  if (state_ != UpdateState::kReceiving) return Error::kInvalidState;
  if (have_last_ && request.offset == last_offset_ && request.length == last_length_) {
    return last_offset_ + last_length_;  // the host lost our Ack: acknowledge again, write nothing
  }
  if (request.offset != next_offset_ || request.length > begin_.image_size - next_offset_) {
    return Error::kInvalidState;
  }
  const uint32_t address = layout_.slots[target_].region.address + request.offset;
  if (!flash_.program(address, protocol::ByteView{request.data.data(), request.length})) {
    flash_failed();
    return Error::kFlashError;
  }
  last_offset_ = request.offset;
  last_length_ = request.length;
  have_last_ = true;
  next_offset_ += request.length;
  return next_offset_;
}

protocol::Result<uint32_t> UpdateReceiver::verify() {
  if (state_ == UpdateState::kVerified) return begin_.crc32c;  // a repeat: the Ack was lost
  if (state_ != UpdateState::kReceiving || next_offset_ != begin_.image_size) return Error::kInvalidState;
  const SlotLayout& slot = layout_.slots[target_];
  const protocol::Result<uint32_t> crc = flash_crc32c(flash_, slot.region.address, begin_.image_size);
  if (!crc) {
    flash_failed();
    return Error::kFlashError;
  }
  const protocol::Result<protocol::ImageHeader> header =
      check_slot_image(flash_, slot, board_, layout_.vector_alignment, begin_.image_size);
  if (*crc != begin_.crc32c || !header || header->fw_version != begin_.version) {
    state_ = UpdateState::kFailed;
    return Error::kImageRejected;
  }
  const uint8_t running = target_ == 0 ? 1 : 0;  // confirmed when no boot state is stored
  if (!mark_slot_pending(store_, target_, begin_.version, running)) {
    flash_failed();
    return Error::kFlashError;
  }
  state_ = UpdateState::kVerified;
  return *crc;
}

protocol::Status UpdateReceiver::abort() {
  if (state_ == UpdateState::kVerified && !clear_pending_slot(store_, target_)) {
    if (flash_errors_ != UINT16_MAX) ++flash_errors_;
    return Error::kFlashError;  // still verified: the slot stays pending
  }
  state_ = UpdateState::kIdle;
  have_last_ = false;
  return {};
}

}  // namespace tetrapulse::fw
