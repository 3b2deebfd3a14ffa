#include "tetrapulse/linux_board/board_error.hpp"

namespace tetrapulse::linux_board {

std::string BoardError::what() const {
  const std::string text = where.empty() ? message : where + ": " + message;
  return kind == BoardErrorKind::kUsbGadget ? "USB gadget: " + text : text;
}

}  // namespace tetrapulse::linux_board
