#pragma once
// What an incremental decoder (UART bytes, USB packets) produced from its latest input.
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

enum class ReceiveKind : uint8_t {
  kNothing,  // input taken, no frame ended
  kMessage,  // a frame ended and held a valid message
  kError,    // a frame ended (or was abandoned) and was invalid
};

struct ReceiveEvent {
  ReceiveKind kind = ReceiveKind::kNothing;
  Error error = Error::kNone;  // when kind == kError
  ByteView message;            // when kind == kMessage; valid until the decoder is fed again

  static ReceiveEvent nothing() { return ReceiveEvent{}; }
  static ReceiveEvent received(ByteView m) { return ReceiveEvent{ReceiveKind::kMessage, Error::kNone, m}; }
  static ReceiveEvent failed(Error e) { return ReceiveEvent{ReceiveKind::kError, e, ByteView{}}; }
};

}  // namespace tetrapulse::protocol
