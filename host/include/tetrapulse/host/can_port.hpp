#pragma once
// One CAN interface as a link sees it: classic frames with 29-bit identifiers out, and
// received frames, error frames and transmit timestamps in, each with a kernel timestamp
// on CLOCK_MONOTONIC (rig_clock.hpp). SocketCanPort is the real one; tests use a fake.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/can_id.hpp"

namespace tetrapulse::host {

struct CanPortEvent {
  enum class Kind {
    kFrame,        // a data frame with an extended identifier
    kError,        // an error frame (linux/can/error.h): `error_class` and `error_data`
    kTxTimestamp,  // when a frame this port sent left the host (SO_TIMESTAMPING tx software)
  };
  Kind kind = Kind::kFrame;
  protocol::CanFrame frame;             // kFrame
  int64_t timestamp_ns = 0;             // CLOCK_MONOTONIC; 0 when the kernel gave none
  bool own = false;                     // kFrame: this port's own frame echoed back
  uint32_t error_class = 0;             // kError: CAN_ERR_* bits of the error frame's identifier
  std::array<uint8_t, 8> error_data{};  // kError: the error frame's data bytes
  uint32_t tx_key = 0;                  // kTxTimestamp: the key send() returned for that frame
};

class CanPort {
 public:
  virtual ~CanPort() = default;  // owned through the base (unique_ptr<CanPort>)
  // "vcan0"
  const std::string& interface_name() const { return do_interface_name(); }
  // Queues one frame for transmission; returns a key that its kTxTimestamp event carries.
  HostResult<uint32_t> send(const protocol::CanFrame& frame) { return do_send(frame); }
  // Waits at most `timeout_ns` for the next event; nullopt when none came.
  HostResult<std::optional<CanPortEvent>> next(int64_t timeout_ns) { return do_next(timeout_ns); }

 private:
  virtual const std::string& do_interface_name() const = 0;
  virtual HostResult<uint32_t> do_send(const protocol::CanFrame& frame) = 0;
  virtual HostResult<std::optional<CanPortEvent>> do_next(int64_t timeout_ns) = 0;
};

struct SocketCanOptions {
  // Acceptance filters (SPEC.md §4.1) on 29-bit identifiers; the port adds CAN_EFF_FLAG so
  // that standard and remote frames never match. Empty: every extended data frame.
  std::vector<protocol::CanFilter> filters;
  bool error_frames = true;    // deliver every class of error frame (CAN_ERR_MASK)
  bool tx_timestamps = false;  // SO_TIMESTAMPING transmit timestamps (software) on the error queue
  bool receive_own = false;    // CAN_RAW_RECV_OWN_MSGS: own frames come back, `own` set
};

// A raw SocketCAN socket bound to `interface_name`, with kernel receive timestamps
// (SO_TIMESTAMPING software, or SO_TIMESTAMPNS where that is refused).
// kNotFound for an unknown interface, kOpenFailed when the socket cannot be set up.
HostResult<std::unique_ptr<CanPort>> open_socketcan(const std::string& interface_name, const SocketCanOptions& options);

// Names of the CAN_ERR_* classes set in `error_class`, e.g. "bus-off, controller".
std::string can_error_class_names(uint32_t error_class);

}  // namespace tetrapulse::host
