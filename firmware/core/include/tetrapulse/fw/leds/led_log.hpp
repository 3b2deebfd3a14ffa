#pragma once
// A ring of the last LED changes the code player scheduled, with sequence numbers, for
// GetLedLog (SPEC.md §2.3) and tests: when (rig and local time), which marker, what duty.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"

namespace tetrapulse::fw {

struct LedLogRecord {
  uint32_t seq = 0;
  int64_t rig_ns = 0;  // the rig time the change is meant for (the code's bit edge)
  Tick local = 0;      // the local tick it was scheduled at
  uint8_t marker = 0;
  uint16_t duty = 0;
};

class LedLog {
 public:
  static constexpr size_t kCapacity = 64;

  void append(int64_t rig_ns, Tick local, uint8_t marker, uint16_t duty);

  // Copies up to `max` records with seq >= first (from the oldest held, if `first` is
  // older), oldest first; returns how many. `*next` is the seq to ask for next.
  size_t read(uint32_t first, LedLogRecord* out, size_t max, uint32_t* next) const;

  uint32_t next_seq() const { return next_seq_; }
  size_t size() const { return count_; }

 private:
  LedLogRecord records_[kCapacity];
  size_t count_ = 0;
  uint32_t next_seq_ = 0;
};

}  // namespace tetrapulse::fw
