#include "tetrapulse/linux_board/gpio_line.hpp"

#include <cctype>
#include <exception>

namespace tetrapulse::linux_board {
namespace {

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  return true;
}

}  // namespace

BoardResult<gpiod::line> find_gpio_line(const std::string& text) {
  const std::string where = "GPIO line '" + text + "'";
  // Chip labels may contain ':' ("gpio-sim.0:node0"), line names do not: split at the last one.
  const size_t colon = text.rfind(':');
  const std::string chip_name = colon == std::string::npos ? std::string() : text.substr(0, colon);
  const std::string line_name = colon == std::string::npos ? text : text.substr(colon + 1);
  if (line_name.empty()) return board_error(BoardErrorKind::kGpio, where, "no line after the chip");
  try {
    gpiod::line line;
    if (chip_name.empty()) {
      line = gpiod::find_line(line_name);
    } else {
      gpiod::chip chip(chip_name, gpiod::chip::OPEN_LOOKUP);
      line = all_digits(line_name) ? chip.get_line(static_cast<unsigned>(std::stoul(line_name)))
                                   : chip.find_line(line_name);
    }
    if (!line) return board_error(BoardErrorKind::kGpio, where, "no such line");
    return line;
  } catch (const std::exception& e) {
    return board_error(BoardErrorKind::kGpio, where, e.what());
  }
}

}  // namespace tetrapulse::linux_board
