#include "tetrapulse/fw/update_receiver.hpp"

namespace tetrapulse::fw {

using protocol::Error;
using protocol::UpdateState;

namespace {

// The slot being written must not stay marked pending: the bootloader would try it.
protocol::Status clear_pending(RecordStore& store, uint8_t slot) {
  const protocol::Result<BootState> state = load_boot_state(store);
  if (!state || state->pending_slot != slot) return {};
  BootState s = *state;
  s.pending_slot = kNoSlot;
  s.attempts = 0;
  s.pending_version = 0;
  return save_boot_state(store, s);
}

}  // namespace

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
  if (!clear_pending(store_, target_)) {
    flash_failed();
    return Error::kFlashError;
  }
  for (uint32_t a = slot.region.address; a < slot.region.end();) {
    const protocol::Result<FlashRegion> sector = flash_.sector_at(a);
    if (!sector || !flash_.erase_sector(sector->address)) {
      flash_failed();
      return Error::kFlashError;
    }
    a = sector->end();
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
  const protocol::Result<BootState> stored = load_boot_state(store_);
  BootState state = stored ? *stored : BootState{};
  if (!stored) state.confirmed_slot = target_ == 0 ? 1 : 0;  // the running slot
  state.pending_slot = target_;
  state.attempts = 0;
  state.pending_version = begin_.version;
  if (!save_boot_state(store_, state)) {
    flash_failed();
    return Error::kFlashError;
  }
  state_ = UpdateState::kVerified;
  return *crc;
}

protocol::Status UpdateReceiver::abort() {
  if (state_ == UpdateState::kVerified && !clear_pending(store_, target_)) {
    if (flash_errors_ != UINT16_MAX) ++flash_errors_;
    return Error::kFlashError;  // still verified: the slot stays pending
  }
  state_ = UpdateState::kIdle;
  have_last_ = false;
  return {};
}

}  // namespace tetrapulse::fw
