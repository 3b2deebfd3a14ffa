#pragma once
// Receives a firmware image into the inactive slot (SPEC.md §7.3): UpdateBegin erases
// the slot, UpdateChunk programs it in order (a repeat of the last chunk is acknowledged
// again without writing), UpdateVerify checks the whole image and marks the slot pending
// in the boot state, UpdateAbort drops it. Every error leaves the running firmware and
// the boot state as they were.
#include <cstdint>

#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/boot/image_check.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/request_messages.hpp"
#include "tetrapulse/protocol/response_messages.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

class UpdateReceiver {
 public:
  UpdateReceiver(Flash& flash, const FlashLayout& layout, RecordStore& store, const BoardModel& board,
                 uint8_t active_slot);

  // Ack values on success (SPEC.md §2.6); errors as §7.3. `detail` gets the ErrorResponse
  // detail (the expected offset's low 16 bits for a misplaced chunk).
  protocol::Result<uint32_t> begin(const protocol::UpdateBegin& request);
  protocol::Result<uint32_t> chunk(const protocol::UpdateChunk& request, uint16_t* detail);
  protocol::Result<uint32_t> verify();
  protocol::Status abort();

  protocol::UpdateState state() const { return state_; }
  // True while an update is writing flash (PersistConfig and FactoryReset are refused).
  bool writing() const { return state_ == protocol::UpdateState::kReceiving; }
  uint8_t target_slot() const { return target_; }
  uint16_t flash_errors() const { return flash_errors_; }

 private:
  void flash_failed();

  Flash& flash_;
  FlashLayout layout_;
  RecordStore& store_;
  BoardModel board_;
  uint8_t target_;
  protocol::UpdateState state_ = protocol::UpdateState::kIdle;
  protocol::UpdateBegin begin_;
  uint32_t next_offset_ = 0;
  uint32_t last_offset_ = 0;
  uint16_t last_length_ = 0;
  bool have_last_ = false;
  uint16_t flash_errors_ = 0;
};

}  // namespace tetrapulse::fw
