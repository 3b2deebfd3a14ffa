#include "tetrapulse/host/host_error.hpp"

namespace tetrapulse::host {

std::string HostError::what() const { return device.empty() ? message : device + ": " + message; }

const char* host_error_kind_name(HostErrorKind kind) {
  switch (kind) {
    case HostErrorKind::kBadInput: return "bad_input";
    case HostErrorKind::kBadFile: return "bad_file";
    case HostErrorKind::kNotFound: return "not_found";
    case HostErrorKind::kOpenFailed: return "open_failed";
    case HostErrorKind::kIo: return "io";
    case HostErrorKind::kDisconnected: return "disconnected";
    case HostErrorKind::kTimeout: return "timeout";
    case HostErrorKind::kMalformed: return "malformed";
    case HostErrorKind::kBoardRefused: return "board_refused";
    case HostErrorKind::kBusOff: return "bus_off";
    case HostErrorKind::kImageRejected: return "image_rejected";
    case HostErrorKind::kVerifyFailed: return "verify_failed";
    case HostErrorKind::kCancelled: return "cancelled";
  }
  return "unknown";
}

}  // namespace tetrapulse::host
