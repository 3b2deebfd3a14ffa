#pragma once
// Which firmware slot the bootloader starts (SPEC.md §7): the boot state record and the
// pure decision the bootloader makes from it and from the checks of both slots.
//
// An update marks its slot pending (UpdateVerify). The bootloader gives a pending slot up
// to kMaxTrialBoots starts, counting each before it jumps; the application confirms
// itself (BootState::confirm) once it is healthy: it has run its main loop for
// kConfirmAfterMs and answered a request on a link (so a further update can reach it).
// A pending slot that used its trials without confirming is dropped and the confirmed
// slot runs again. A slot whose image fails the checks is never started.
#include <array>
#include <cstdint>

#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

constexpr uint8_t kMaxTrialBoots = 3;
constexpr uint32_t kConfirmAfterMs = 5'000;

struct BootState {
  uint8_t confirmed_slot = kNoSlot;  // the last image that confirmed itself
  uint8_t pending_slot = kNoSlot;    // verified by an update, not confirmed yet
  uint8_t attempts = 0;              // trial starts of pending_slot so far
  uint32_t pending_version = 0;      // its fw_version (for logs)

  bool operator==(const BootState& o) const {
    return confirmed_slot == o.confirmed_slot && pending_slot == o.pending_slot &&
           attempts == o.attempts && pending_version == o.pending_version;
  }
  bool operator!=(const BootState& o) const { return !(*this == o); }
};
constexpr size_t kBootStateSize = 8;

protocol::Status encode_boot_state(const BootState& state, uint8_t (&out)[kBootStateSize]);
protocol::Result<BootState> decode_boot_state(protocol::ByteView in);

// The stored boot state (kInvalidState when none, e.g. a board fresh from the factory).
protocol::Result<BootState> load_boot_state(const RecordStore& store);
protocol::Status save_boot_state(RecordStore& store, const BootState& state);

// What the bootloader found in a slot.
struct SlotCheck {
  bool valid = false;       // header, fits, load_address and payload CRC all pass
  uint32_t fw_version = 0;  // when valid
};

struct BootDecision {
  bool boot = false;              // false: stay in the bootloader (no valid slot, or asked to)
  uint8_t slot = kNoSlot;         // when boot
  bool write_state = false;       // store `state` before jumping
  BootState state;
};

// The bootloader's choice. `stay` (Reboot{bootloader}) keeps it in the bootloader.
// With no stored state, the valid slot with the highest version runs as confirmed.
BootDecision select_boot(const protocol::Result<BootState>& stored,
                         const std::array<SlotCheck, kSlotCount>& slots, bool stay);

// The application's side: the state after slot `running` confirmed itself, or nullopt
// semantics through `changed` = false when nothing needs writing.
BootState confirm_slot(const BootState& state, uint8_t running, bool* changed);

}  // namespace tetrapulse::fw
