#pragma once
// Why the Linux board cannot start or go on: which of its parts failed, on which file, line
// or interface, and what happened there. main() prints what() as the board's one error line.
#include <string>

#include <tl/expected.hpp>

namespace tetrapulse::linux_board {

enum class BoardErrorKind {
  kFlash,         // the flash file: cannot be created, opened, read or written, or has the wrong size
  kFactoryImage,  // --factory-image: unreadable, not a firmware image, or not one for this board
  kGpio,          // an LED or sync-input GPIO line: no such line, or it cannot be requested
  kCan,           // the CAN interface: missing, or its socket cannot be set up
  kUsbGadget,     // the configfs USB gadget or its FunctionFS function
  kNoImage,       // no valid image in either slot and no way to receive one
};

struct BoardError {
  BoardErrorKind kind = BoardErrorKind::kFlash;
  std::string where;    // the file, line or interface: "/var/lib/tetrapulse-board/flash.bin", "GPIO line 'led0'"
  std::string message;  // what failed there: "cannot create: Permission denied"

  // "where: message", after "USB gadget: " for the gadget's errors (a configfs or FunctionFS
  // path alone does not say what it is).
  std::string what() const;
};

template <typename T>
using BoardResult = tl::expected<T, BoardError>;

inline tl::unexpected<BoardError> board_error(BoardErrorKind kind, std::string where, std::string message) {
  return tl::unexpected<BoardError>(BoardError{kind, std::move(where), std::move(message)});
}

}  // namespace tetrapulse::linux_board
