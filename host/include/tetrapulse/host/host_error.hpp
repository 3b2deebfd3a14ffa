#pragma once
// Errors of the host driver: what went wrong and with which device or file.
#include <string>

#include <tl/expected.hpp>

#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::host {

enum class HostErrorKind {
  kBadInput,       // a board address, option or value that does not parse or is out of range
  kBadFile,        // an input file is missing, unreadable or malformed (images, board configs)
  kNotFound,       // no such board, interface, serial port or GPIO line
  kOpenFailed,     // it exists but cannot be opened (permissions, busy)
  kIo,             // the link failed while in use
  kDisconnected,   // the board went away and did not come back in time
  kTimeout,        // no answer in time
  kMalformed,      // the board answered with something that is not the expected response
  kBoardRefused,   // the board answered ErrorResponse
  kBusOff,         // the CAN controller is bus-off
  kImageRejected,  // a firmware image does not fit the board (checked by the host)
  kVerifyFailed,   // a check after an operation did not hold (read-back, CRC, version)
  kCancelled,      // stopped by the caller
};

struct HostError {
  HostErrorKind kind = HostErrorKind::kIo;
  std::string device;   // "usb:0123ABCD", "can:vcan0:3", "serial:/dev/ttyUSB0", "sim:1" or a file path
  std::string message;  // what failed: "get_info: no answer within 1000 ms"
  protocol::Error protocol_error = protocol::Error::kNone;  // the board's or decoder's error, when there is one

  // "can:vcan0:3: set_config: board refused: not_supported"
  std::string what() const;
};

template <typename T>
using HostResult = tl::expected<T, HostError>;

inline tl::unexpected<HostError> host_error(HostErrorKind kind, std::string device, std::string message,
                                            protocol::Error protocol_error = protocol::Error::kNone) {
  return tl::unexpected<HostError>(HostError{kind, std::move(device), std::move(message), protocol_error});
}

// A short name for logs ("timeout", "board_refused").
const char* host_error_kind_name(HostErrorKind kind);

}  // namespace tetrapulse::host
