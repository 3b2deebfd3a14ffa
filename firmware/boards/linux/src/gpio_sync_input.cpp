#include "tetrapulse/linux_board/gpio_sync_input.hpp"

#include <exception>

#include "tetrapulse/linux_board/gpio_line.hpp"

namespace tetrapulse::linux_board {

BoardResult<std::unique_ptr<GpioSyncInput>> GpioSyncInput::open(const MonotonicClock& clock, const std::string& line) {
  BoardResult<gpiod::line> found = find_gpio_line(line);
  if (!found) return tl::unexpected(found.error());
  return std::unique_ptr<GpioSyncInput>(new GpioSyncInput(clock, line, std::move(*found)));
}

int GpioSyncInput::fd() const {
  if (!enabled_) return -1;
  try {
    return line_.event_get_fd();
  } catch (const std::exception&) {
    return -1;
  }
}

std::vector<fw::Tick> GpioSyncInput::read_edges() {
  std::vector<fw::Tick> ticks;
  if (!enabled_) return ticks;
  try {
    for (const gpiod::line_event& e : line_.event_read_multiple()) {
      ticks.push_back(clock_.at(static_cast<int64_t>(e.timestamp.count())));
    }
  } catch (const std::exception& e) {
    problem_ = "sync input '" + name_ + "': " + e.what();
  }
  return ticks;
}

void GpioSyncInput::do_configure(bool enabled, protocol::GpioEdge edge) {
  problem_.clear();
  try {
    if (line_.is_requested()) line_.release();
    enabled_ = false;
    if (!enabled) return;
    const int type = edge == protocol::GpioEdge::kRising ? gpiod::line_request::EVENT_RISING_EDGE
                                                          : gpiod::line_request::EVENT_FALLING_EDGE;
    line_.request({"tetrapulse-board", type, 0});
    enabled_ = true;
  } catch (const std::exception& e) {
    problem_ = "sync input '" + name_ + "': " + e.what();
  }
}

}  // namespace tetrapulse::linux_board
