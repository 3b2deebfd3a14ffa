#pragma once
// The Linux board's CAN controller: a raw SocketCAN socket with the node's acceptance
// filters (SPEC.md §4.1) in the kernel, extended data frames only, error frames counted
// and bus-off noted. Received frames carry the kernel's receive timestamp (software, at
// the driver), converted to local ticks: that is the capture time CAN time sync needs.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/linux_board/monotonic_clock.hpp"

namespace tetrapulse::linux_board {

struct ReceivedCanFrame {
  protocol::CanFrame frame;
  fw::Tick rx = 0;
};

class SocketCanBus final : public fw::CanBus {
 public:
  // kCan at "CAN interface 'NAME'" when it is missing or its socket cannot be set up.
  static BoardResult<std::unique_ptr<SocketCanBus>> open(const std::string& interface_name, const MonotonicClock& clock);
  ~SocketCanBus();
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  int fd() const { return fd_; }
  // The next data frame waiting (error frames are counted on the way), or nullopt.
  std::optional<ReceivedCanFrame> receive();

 private:
  SocketCanBus(int fd, std::string name, const MonotonicClock& clock) : fd_(fd), name_(std::move(name)), clock_(clock) {}
  protocol::Status do_send(const protocol::CanFrame& frame) override;
  void do_set_filters(const protocol::CanNodeFilters& filters) override;
  uint16_t do_error_count() const override { return errors_; }
  bool do_bus_off() const override { return bus_off_; }

  int fd_;
  std::string name_;
  const MonotonicClock& clock_;
  uint16_t errors_ = 0;
  bool bus_off_ = false;
};

}  // namespace tetrapulse::linux_board
