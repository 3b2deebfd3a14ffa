#include "tetrapulse/fw/boot/boot_slot.hpp"

#include "tetrapulse/fw/boot/slot_survey.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"

namespace tetrapulse::fw {

BootChoice choose_boot_slot(Flash& flash, const FlashLayout& layout, const BoardModel& board, bool stay) {
  RecordStore store(flash, layout.record_sectors);
  const SlotSurvey survey = survey_slots(store, flash, layout, board);
  const protocol::Result<BootState>& stored = survey.stored;
  BootDecision d = select_boot(stored, survey.checks, stay);
  BootChoice choice;
  if (d.write_state) choice.state_written = save_boot_state(store, d.state).ok();
  if (!choice.state_written && d.boot && d.slot == d.state.pending_slot && stored) {
    // A trial start that could not be counted might repeat forever: run the confirmed
    // image instead.
    BootState without_trial = *stored;
    without_trial.pending_slot = kNoSlot;
    d = select_boot(without_trial, survey.checks, stay);
  }
  choice.boot = d.boot;
  choice.slot = d.slot;
  if (d.boot) choice.header = survey.headers[d.slot];
  return choice;
}

}  // namespace tetrapulse::fw
