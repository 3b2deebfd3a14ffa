#pragma once
// Answers every protocol request (SPEC.md §2.3, §3) and takes the time-sync broadcasts
// (§2.4). A message that fails to decode, or a request that cannot be carried out, gets
// a typed ErrorResponse and changes nothing but the diagnostic counters (rx_malformed,
// last_error). Inputs shorter than 3 bytes, malformed time-sync messages and responses
// are dropped and counted; Sync, FollowUp and responses are never answered.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/app/board_state.hpp"
#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::fw {

struct CommandReply {
  size_t size = 0;                  // bytes of the response written to `out`; 0: no response
  bool reboot = false;              // reset after the response has been sent
  protocol::RebootMode reboot_mode = protocol::RebootMode::kApplication;
};

class CommandHandler {
 public:
  explicit CommandHandler(BoardState& board) : board_(board) {}

  // One received message (its bytes, local reception tick and link kind); the response
  // goes to `out` (kMaxMessageSize bytes suffice).
  CommandReply handle(protocol::ByteView message, Tick rx_tick, LinkKind link, uint8_t* out, size_t capacity);

 private:
  protocol::Result<protocol::Body> execute(const protocol::Message& request, CommandReply& reply, uint16_t* detail);

  BoardState& board_;
};

}  // namespace tetrapulse::fw
