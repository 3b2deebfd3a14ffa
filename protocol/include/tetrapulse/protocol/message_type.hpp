#pragma once
// Message type codes (SPEC.md §2). The numeric values are wire values: never renumber.
#include <cstdint>

namespace tetrapulse::protocol {

enum class MessageType : uint8_t {
  // Requests, host -> board (0x01-0x3F); each is answered by one response with the same seq.
  kGetInfo = 0x01,
  kGetConfig = 0x02,
  kSetConfig = 0x03,
  kGetStatus = 0x04,
  kIdentify = 0x05,
  kPersistConfig = 0x06,
  kFactoryReset = 0x07,
  kReboot = 0x08,
  kUpdateBegin = 0x10,
  kUpdateChunk = 0x11,
  kUpdateVerify = 0x12,
  kUpdateAbort = 0x13,
  kGetLedLog = 0x20,
  // Time sync, broadcast by the sync master (0x40-0x4F); never answered.
  kSync = 0x40,
  kFollowUp = 0x41,
  // Responses, board -> host (0x80-0xFF).
  kAck = 0x80,
  kInfo = 0x81,
  kConfigReport = 0x82,
  kStatusReport = 0x83,
  kLedLog = 0x84,
  kErrorResponse = 0xFF,
};

// Which range a type code falls in (whether or not the code is defined).
constexpr bool is_request(MessageType t) { return t >= MessageType::kGetInfo && static_cast<uint8_t>(t) <= 0x3F; }
constexpr bool is_time_sync(MessageType t) { return static_cast<uint8_t>(t) >= 0x40 && static_cast<uint8_t>(t) <= 0x4F; }
constexpr bool is_response(MessageType t) { return static_cast<uint8_t>(t) >= 0x80; }

// The snake_case name of a defined type ("set_config"), "unknown" otherwise. Never null.
const char* message_name(MessageType t);

// True for the codes listed above.
bool is_defined(MessageType t);

}  // namespace tetrapulse::protocol
