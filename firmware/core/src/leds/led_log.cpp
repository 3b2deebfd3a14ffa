#include "tetrapulse/fw/leds/led_log.hpp"

namespace tetrapulse::fw {

void LedLog::append(int64_t rig_ns, Tick local, uint8_t marker, uint16_t duty) {
  const size_t slot = next_seq_ % kCapacity;
  records_[slot] = LedLogRecord{next_seq_, rig_ns, local, marker, duty};
  ++next_seq_;
  if (count_ < kCapacity) ++count_;
}

size_t LedLog::read(uint32_t first, LedLogRecord* out, size_t max, uint32_t* next) const {
  const uint32_t oldest = next_seq_ - static_cast<uint32_t>(count_);
  // Sequence numbers wrap; compare by distance from the oldest record held.
  uint32_t seq = first;
  if (static_cast<uint32_t>(first - oldest) > static_cast<uint32_t>(count_)) {
    if (static_cast<int32_t>(first - next_seq_) > 0) {  // not scheduled yet: nothing, ask again
      *next = first;
      return 0;
    }
    seq = oldest;  // older than the ring holds: start at the oldest (the caller sees the gap)
  }
  size_t n = 0;
  while (n < max && seq != next_seq_) {
    out[n++] = records_[seq % kCapacity];
    ++seq;
  }
  *next = seq;
  return n;
}

}  // namespace tetrapulse::fw
