#include "tetrapulse/fw/boot/slot_survey.hpp"

#include "tetrapulse/fw/boot/update_slot.hpp"

namespace tetrapulse::fw {

uint8_t SlotSurvey::known_good() const { return known_good_slot(stored, checks); }
uint8_t SlotSurvey::update_target() const { return update_target_slot(stored, checks); }

SlotSurvey survey_slots(RecordStore& store, const Flash& flash, const FlashLayout& layout, const BoardModel& board) {
  static_cast<void>(store.open());  // unreadable: empty
  SlotSurvey survey;
  for (uint8_t s = 0; s < kSlotCount; ++s) {
    const protocol::Result<protocol::ImageHeader> h =
        check_slot_image(flash, layout.slots[s], board, layout.vector_alignment);
    if (h) {
      survey.checks[s] = SlotCheck{true, h->fw_version};
      survey.headers[s] = *h;
    }
  }
  survey.stored = load_boot_state(store);
  return survey;
}

}  // namespace tetrapulse::fw
