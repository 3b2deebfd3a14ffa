#pragma once
// A CAN bus of the virtual rig as a CanPort: what the host sends goes on the bus at the
// bus's simulated rig time and reaches every attached simulated board (firmware/boards/sim)
// that is connected then. Each board receives a Sync (the frame whose reception it
// time-stamps) `sync_latency()` ns late; other frames arrive as they go out. The port gives
// a transmit timestamp for every frame at once, and reading one lets `turnaround_ns` of bus
// time pass: the host's reaction before its next frame (CanSync's FollowUp).
//
// Timestamps are "monotonic" to a RigClock, rig_clock(): rig time + 2^60, so that no rig
// time (negative ones included) gives the 0 that means "no timestamp".
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/can_port.hpp"
#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::host {

class SimCanBus final : public CanPort {
 public:
  explicit SimCanBus(std::string interface_name = "simcan0", int64_t turnaround_ns = 1'000'000)
      : name_(std::move(interface_name)), turnaround_ns_(turnaround_ns) {}

  // `connected(t)`: whether the board hears the bus at rig time t.
  void attach(std::shared_ptr<sim_board::SimBoard> board, std::function<int64_t()> sync_latency,
              std::function<bool(int64_t)> connected);
  // Frames sent from now on go on the bus at rig time `rig_ns` (never earlier than before);
  // transmit timestamps not read by then are dropped.
  void set_time(int64_t rig_ns);
  int64_t time() const { return now_; }
  RigClock rig_clock() const { return RigClock(-kStampOffsetNs); }
  size_t frames_sent() const { return frames_sent_; }

 private:
  const std::string& do_interface_name() const override { return name_; }
  HostResult<uint32_t> do_send(const protocol::CanFrame& frame) override;
  HostResult<std::optional<CanPortEvent>> do_next(int64_t timeout_ns) override;

  static constexpr int64_t kStampOffsetNs = int64_t{1} << 60;
  struct Node {
    std::shared_ptr<sim_board::SimBoard> board;
    std::function<int64_t()> sync_latency;
    std::function<bool(int64_t)> connected;
  };

  std::string name_;
  int64_t turnaround_ns_;
  int64_t now_ = INT64_MIN;
  uint32_t next_key_ = 1;
  size_t frames_sent_ = 0;
  std::vector<Node> nodes_;
  std::deque<CanPortEvent> events_;
};

}  // namespace tetrapulse::host
