#pragma once
// The CAN sync master (protocol/SPEC.md §2.4): broadcasts Sync{seq} at a fixed rate and,
// once it knows when that frame really left, FollowUp{seq, tx_time_ns} with the transmit
// time in rig time. The transmit time comes, best first, from
//  - the kernel's transmit timestamp (SO_TIMESTAMPING, software: the driver handing the
//    frame to the controller; vcan and most drivers give it),
//  - the receive timestamp of the frame's own echo (CAN_RAW_RECV_OWN_MSGS; on controllers
//    that echo on transmit completion this is the end of the frame on the bus),
//  - the time send() returned (no kernel timestamp at all; the error is the queueing delay).
// Syncs go out at rig times start + k * period (CLOCK_MONOTONIC absolute sleeps).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "tetrapulse/host/can_port.hpp"
#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::host {

enum class TxStampSource { kKernelTransmit, kOwnEcho, kSendCall };
const char* tx_stamp_source_name(TxStampSource source);  // "kernel-tx", "own-echo", "send-call"

struct CanSyncSample {
  uint16_t sync_seq = 0;
  int64_t tx_time_ns = 0;  // rig time the Sync left, as sent in its FollowUp
  TxStampSource source = TxStampSource::kKernelTransmit;
};

struct CanSyncOptions {
  int64_t period_ns = 100'000'000;  // 10 Hz
  // How long to wait for a kernel timestamp of a Sync before falling back (once an
  // interface has not given one, it is not waited for again).
  std::chrono::milliseconds stamp_wait{50};
};

class CanSync {
 public:
  // A raw socket on `interface_name` with transmit timestamps and own-frame echoes.
  static HostResult<std::unique_ptr<CanSync>> open(const std::string& interface_name, RigClock clock,
                                                   CanSyncOptions options = {});
  // Over any port (tests use a fake); it should deliver tx timestamps and/or own echoes.
  CanSync(std::unique_ptr<CanPort> port, RigClock clock, CanSyncOptions options);

  // One Sync and its FollowUp, now.
  HostResult<CanSyncSample> send_one();
  // Syncs at the configured rate until `stop` is set or `max_count` were sent (0: no limit).
  HostResult<uint64_t> run(const std::atomic<bool>& stop, uint64_t max_count,
                           const std::function<void(const CanSyncSample&)>& on_sample);

  const std::string& name() const { return name_; }

 private:
  HostResult<void> send_message(const protocol::Message& m, uint32_t* first_key, protocol::CanFrame* first_frame);

  std::unique_ptr<CanPort> port_;
  std::string name_;
  RigClock clock_;
  CanSyncOptions options_;
  protocol::CanTransferSender sender_{protocol::kCanHostNode};
  uint16_t seq_ = 0;
  bool kernel_tx_stamps_ = true;  // until an interface is seen without them
};

}  // namespace tetrapulse::host
