#pragma once
// A protocol message and its byte encoding (SPEC.md §2):
//   [version u8 = kProtocolVersion][type u8][seq u8][body: the fields of the type, in order]
// Every transport carries exactly these bytes.
#include <cstddef>
#include <cstdint>
#include <variant>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/message_type.hpp"
#include "tetrapulse/protocol/request_messages.hpp"
#include "tetrapulse/protocol/response_messages.hpp"
#include "tetrapulse/protocol/result.hpp"
#include "tetrapulse/protocol/time_sync_messages.hpp"

namespace tetrapulse::protocol {

// Every defined message; a new message is a new alternative here and a MessageType code.
using Body = std::variant<GetInfo, GetConfig, SetConfig, GetStatus, Identify, PersistConfig,
                          FactoryReset, Reboot, UpdateBegin, UpdateChunk, UpdateVerify,
                          UpdateAbort, GetLedLog, Sync, FollowUp, Ack, Info, ConfigReport,
                          StatusReport, LedLog, ErrorResponse>;

struct Message {
  uint8_t seq = 0;  // chosen by the requester, echoed by the response
  Body body;

  MessageType type() const;
  template <class T>
  const T* get() const { return std::get_if<T>(&body); }
};

// Bytes in the envelope before the body.
constexpr size_t kMessageHeaderSize = 3;

// kBadValue / kBadLength when a field is outside its range (SPEC.md §2); checks the body only.
Status validate(const Message& message);

// Validates, then appends the encoding to `out`: kBufferTooSmall if it does not fit
// (then `out` holds a partial message and must be discarded).
Status encode(const Message& message, ByteWriter& out);

// Decodes exactly one message filling all of `in`. Checks, in this order: the version
// (kBadVersion), the type (kUnknownMessage), the fields as they are read (kTruncated;
// kBadLength when a count disagrees with the bytes after it), their values (kBadValue,
// kBadLength), and leftover bytes (kTrailingBytes). Never reads outside `in`.
Result<Message> decode(ByteView in);

// As decode(in); on failure `*stopped_at` is the byte offset where decoding stopped,
// what ErrorResponse.detail carries (SPEC.md §3): 0 for kBadVersion, 1 for kUnknownMessage,
// the start of the field that runs past the end for kTruncated, the offset after the count
// for a count the bytes disagree with, the end of the last field for a value check or
// kTrailingBytes. Untouched on success; `stopped_at` must not be null.
Result<Message> decode(ByteView in, size_t* stopped_at);

// One line naming the message and every field ("identify seq=7 pattern=2 duration_ms=500"),
// for logs and tests. Writes at most `capacity` bytes including the terminating NUL and
// returns the length the whole line needs (like snprintf).
size_t format_message(const Message& message, char* out, size_t capacity);

}  // namespace tetrapulse::protocol
