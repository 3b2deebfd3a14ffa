#include "tetrapulse/fw/boot/boot_state.hpp"

namespace tetrapulse::fw {
namespace {

bool valid_slot_field(uint8_t slot) { return slot < kSlotCount || slot == kNoSlot; }

// The valid slot with the highest version (slot 0 on a tie), or kNoSlot.
uint8_t newest_valid(const std::array<SlotCheck, kSlotCount>& slots) {
  uint8_t best = kNoSlot;
  for (uint8_t s = 0; s < kSlotCount; ++s) {
    if (slots[s].valid && (best == kNoSlot || slots[s].fw_version > slots[best].fw_version)) best = s;
  }
  return best;
}

}  // namespace

protocol::Status encode_boot_state(const BootState& state, uint8_t (&out)[kBootStateSize]) {
  if (!valid_slot_field(state.confirmed_slot) || !valid_slot_field(state.pending_slot)) {
    return protocol::Error::kBadValue;
  }
  protocol::ByteWriter w(out, sizeof(out));
  w.u8(state.confirmed_slot);
  w.u8(state.pending_slot);
  w.u8(state.attempts);
  w.u8(0);
  w.u32(state.pending_version);
  return {};
}

protocol::Result<BootState> decode_boot_state(protocol::ByteView in) {
  if (in.size < kBootStateSize) return protocol::Error::kTruncated;
  if (in.size > kBootStateSize) return protocol::Error::kTrailingBytes;
  protocol::ByteReader r(in);
  BootState s;
  s.confirmed_slot = r.u8();
  s.pending_slot = r.u8();
  s.attempts = r.u8();
  const uint8_t reserved = r.u8();
  s.pending_version = r.u32();
  if (!valid_slot_field(s.confirmed_slot) || !valid_slot_field(s.pending_slot) || reserved != 0) {
    return protocol::Error::kBadValue;
  }
  return s;
}

protocol::Result<BootState> load_boot_state(const RecordStore& store) {
  uint8_t buf[kBootStateSize];
  const protocol::Result<size_t> n = store.read(kBootStateRecordKey, buf, sizeof(buf));
  if (!n) return n.error();
  return decode_boot_state(protocol::ByteView{buf, *n});
}

protocol::Status save_boot_state(RecordStore& store, const BootState& state) {
  uint8_t buf[kBootStateSize];
  const protocol::Status s = encode_boot_state(state, buf);
  if (!s) return s;
  return store.write(kBootStateRecordKey, protocol::ByteView{buf, sizeof(buf)});
}

BootDecision select_boot(const protocol::Result<BootState>& stored, const std::array<SlotCheck, kSlotCount>& slots,
                         bool stay) {
  BootDecision d;
  if (stay) return d;
  // No stored state: fresh from the factory (or unreadable), handled as nothing confirmed.
  BootState s = stored ? *stored : BootState{};
  if (s.pending_slot != kNoSlot) {
    if (slots[s.pending_slot].valid && s.attempts < kMaxTrialBoots) {
      ++s.attempts;  // counted before the jump: a trial that hangs or resets still counts
      d.boot = true;
      d.slot = s.pending_slot;
      d.state = s;
      d.write_state = true;
      return d;
    }
    s.pending_slot = kNoSlot;  // its trials are used up (or it no longer checks): fall back
    s.attempts = 0;
    s.pending_version = 0;
    d.write_state = true;
  }
  if (s.confirmed_slot != kNoSlot && slots[s.confirmed_slot].valid) {
    d.boot = true;
    d.slot = s.confirmed_slot;
    d.state = s;
    return d;
  }
  // The confirmed image is gone, or there never was one: the newest image that checks runs
  // as confirmed (anything is better than no firmware at all).
  const uint8_t slot = newest_valid(slots);
  d.state = s;
  if (slot == kNoSlot) return d;
  d.boot = true;
  d.slot = slot;
  d.state.confirmed_slot = slot;
  d.write_state = true;
  return d;
}

BootState confirm_slot(const BootState& state, uint8_t running, bool* changed) {
  BootState s = state;
  *changed = false;
  if (s.pending_slot == running) {
    s.confirmed_slot = running;
    s.pending_slot = kNoSlot;
    s.attempts = 0;
    s.pending_version = 0;
    *changed = true;
  } else if (s.pending_slot == kNoSlot && s.confirmed_slot != running) {
    s.confirmed_slot = running;
    *changed = true;
  }
  return s;
}

}  // namespace tetrapulse::fw
