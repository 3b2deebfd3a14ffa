#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

const char* error_name(Error e) {
  switch (e) {
    case Error::kNone: return "none";
    case Error::kTruncated: return "truncated";
    case Error::kBadVersion: return "bad_version";
    case Error::kUnknownMessage: return "unknown_message";
    case Error::kBadLength: return "bad_length";
    case Error::kBadValue: return "bad_value";
    case Error::kBadCrc: return "bad_crc";
    case Error::kTrailingBytes: return "trailing_bytes";
    case Error::kBadFraming: return "bad_framing";
    case Error::kBufferTooSmall: return "buffer_too_small";
    case Error::kNotSupported: return "not_supported";
    case Error::kBusy: return "busy";
    case Error::kInvalidState: return "invalid_state";
    case Error::kFlashError: return "flash_error";
    case Error::kImageRejected: return "image_rejected";
    case Error::kAccessDenied: return "access_denied";
    case Error::kTimeout: return "timeout";
  }
  return "unknown_error";
}

}  // namespace tetrapulse::protocol
