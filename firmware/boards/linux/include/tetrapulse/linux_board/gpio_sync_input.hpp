#pragma once
// The Linux board's GPIO sync input (camera strobe or trigger line): line events from the
// kernel, time-stamped by the kernel at the interrupt (CLOCK_MONOTONIC, uAPI v1 on Linux
// >= 5.7), converted to local ticks. That kernel timestamp plays the part of a timer input
// capture: how late user space reads the event does not matter.
#include <memory>
#include <string>
#include <vector>

#include <gpiod.hpp>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/sync/sync_input.hpp"
#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/linux_board/monotonic_clock.hpp"

namespace tetrapulse::linux_board {

class GpioSyncInput final : public fw::SyncInput {
 public:
  // `line`: "CHIP:LINE" or a line name (kGpio when there is none); the line is requested
  // for events only once configure() enables it.
  static BoardResult<std::unique_ptr<GpioSyncInput>> open(const MonotonicClock& clock, const std::string& line);

  // The file descriptor to poll while enabled, -1 otherwise.
  int fd() const;
  // The captured ticks of the events waiting (call when fd() is readable).
  std::vector<fw::Tick> read_edges();
  // The last configure() that failed, or empty.
  const std::string& problem() const { return problem_; }

 private:
  GpioSyncInput(const MonotonicClock& clock, std::string name, gpiod::line line)
      : clock_(clock), name_(std::move(name)), line_(std::move(line)) {}
  void do_configure(bool enabled, protocol::GpioEdge edge) override;

  const MonotonicClock& clock_;
  std::string name_;
  gpiod::line line_;
  bool enabled_ = false;
  std::string problem_;
};

}  // namespace tetrapulse::linux_board
