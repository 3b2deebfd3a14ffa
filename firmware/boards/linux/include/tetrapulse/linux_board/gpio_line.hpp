#pragma once
// A GPIO line of the Linux board, named on its command line as CHIP:LINE (CHIP a gpiochip
// name, path, label or number; LINE an offset or a line name) or as a line name alone,
// looked up on every chip. Requested through libgpiod 1.6 (uAPI v1).
#include <string>

#include <gpiod.hpp>

#include "tetrapulse/linux_board/board_error.hpp"

namespace tetrapulse::linux_board {

// The line `text` names; kGpio at "GPIO line 'text'" when there is none or its chip cannot be opened.
BoardResult<gpiod::line> find_gpio_line(const std::string& text);

}  // namespace tetrapulse::linux_board
