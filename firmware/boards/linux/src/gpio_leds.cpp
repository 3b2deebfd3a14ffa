#include "tetrapulse/linux_board/gpio_leds.hpp"

#include <exception>

#include "tetrapulse/linux_board/gpio_line.hpp"

namespace tetrapulse::linux_board {

using protocol::Error;

BoardResult<std::unique_ptr<GpioLeds>> GpioLeds::open(const fw::LocalClock& clock, const std::vector<std::string>& lines) {
  if (lines.size() > fw::kLedCount) {
    return board_error(BoardErrorKind::kGpio, "",
                       "at most " + std::to_string(fw::kLedCount) + " LED lines, got " + std::to_string(lines.size()));
  }
  std::unique_ptr<GpioLeds> leds(new GpioLeds(clock));
  for (size_t i = 0; i < lines.size(); ++i) {
    BoardResult<gpiod::line> line = find_gpio_line(lines[i]);
    if (!line) return tl::unexpected(line.error());
    try {
      line->request({"tetrapulse-board", gpiod::line_request::DIRECTION_OUTPUT, 0}, 0);
    } catch (const std::exception& e) {
      return board_error(BoardErrorKind::kGpio, "LED " + std::to_string(i) + " on GPIO line '" + lines[i] + "'", e.what());
    }
    leds->lines_[i] = *line;
  }
  return leds;
}

void GpioLeds::drive(uint8_t index, uint16_t duty) {
  if (!lines_[index]) return;
  try {
    lines_[index].set_value(duty > 0 ? 1 : 0);
  } catch (const std::exception&) {
    // A line that cannot be set now is set again by the next change.
  }
}

std::optional<fw::Tick> GpioLeds::next_due() const {
  std::optional<fw::Tick> due;
  for (const auto& queue : pending_) {
    if (!queue.empty() && (!due || queue.front().at < *due)) due = queue.front().at;
  }
  return due;
}

void GpioLeds::apply_due(fw::Tick now) {
  for (uint8_t i = 0; i < fw::kLedCount; ++i) {
    while (!pending_[i].empty() && pending_[i].front().at <= now) {
      const Change c = pending_[i].front();
      pending_[i].pop_front();
      drive(i, c.duty);
      const int64_t late = static_cast<int64_t>(clock_.now() - c.at);
      ++lateness_.applied;
      lateness_.last_ns = late;
      if (late > lateness_.max_ns) lateness_.max_ns = late;
    }
  }
}

protocol::Status GpioLeds::do_schedule(uint8_t index, uint16_t duty, fw::Tick at) {
  if (index >= fw::kLedCount) return Error::kBadValue;
  if (pending_[index].size() >= kQueueDepth) return Error::kBusy;
  if (at < clock_.now() + kLeadTicks) return Error::kInvalidState;
  pending_[index].push_back({at, duty});
  return {};
}

size_t GpioLeds::do_pending(uint8_t index) const { return index < fw::kLedCount ? pending_[index].size() : 0; }

void GpioLeds::do_cancel() {
  for (auto& queue : pending_) queue.clear();
}

void GpioLeds::do_set_now(uint8_t index, uint16_t duty) {
  if (index < fw::kLedCount) drive(index, duty);
}

}  // namespace tetrapulse::linux_board
