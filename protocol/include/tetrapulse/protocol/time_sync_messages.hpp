#pragma once
// Two-step time sync, broadcast by the sync master and never answered (SPEC.md §2.4).
// A board time-stamps Sync on reception; FollowUp then says when the master sent it. Both
// times denote the end of the frame that carries the Sync (SPEC.md §2.4).
#include <cstdint>

#include "tetrapulse/protocol/message_type.hpp"

namespace tetrapulse::protocol {

struct Sync {
  static constexpr MessageType kType = MessageType::kSync;
  uint16_t sync_seq = 0;  // increments per Sync; pairs it with its FollowUp

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("sync_seq", m.sync_seq);
  }
};

struct FollowUp {
  static constexpr MessageType kType = MessageType::kFollowUp;
  uint16_t sync_seq = 0;   // the Sync this follows
  int64_t tx_time_ns = 0;  // rig ns at the end of that Sync's frame on the link

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("sync_seq", m.sync_seq);
    io.field("tx_time_ns", m.tx_time_ns);
  }
};

}  // namespace tetrapulse::protocol
