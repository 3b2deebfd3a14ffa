#pragma once
// A Linux computer as a tetrapulse target board: the firmware core (tetrapulse/fw) on
// CLOCK_MONOTONIC, LEDs on GPIO lines, a GPIO sync input, SocketCAN and a FunctionFS USB
// gadget (message interface + DFU), with its flash in a file.
//
// run_board() is one boot: it opens the flash file (creating it from the factory image
// when missing), lets the core's boot selection pick a slot, and runs either the
// application (Firmware) or, with no valid image or when asked to stay, the DFU-mode
// bootloader (DfuDevice + ImageBundleWriter into the inactive slot). It returns when the
// board resets, with the mode the reset asks for (kBootloader: the bootloader stays): the
// caller re-executes the daemon, so every reset is a fresh start from flash, as on a
// microcontroller. Or it returns the error that keeps the board from running.
#include <cstdint>
#include <string>
#include <vector>

#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/linux_board/linux_system.hpp"
#include "tetrapulse/protocol/request_messages.hpp"

namespace tetrapulse::linux_board {

struct LinuxBoardOptions {
  std::string flash_path = "/var/lib/tetrapulse-board/flash.bin";
  std::string factory_image;     // programmed into slot 0 when the flash file is created
  uint8_t node_id = 1;           // the factory configuration's CAN node id
  BoardSerial serial{};
  std::string can_interface;     // empty: no CAN
  std::vector<std::string> led_lines;  // marker 0..3
  std::string sync_line;         // empty: no GPIO sync input
  std::string usb_gadget;        // configfs gadget name; empty: no USB
  std::string usb_mount;         // FunctionFS mount point (default /dev/ffs-<gadget>)
  std::string usb_udc;           // empty: the first UDC
  double clock_ppm = 0;          // rate error of the local clock (tests)
  bool report_clock = false;     // a clock line on stdout every second
  int dfu_idle_s = 10;           // DFU mode returns to a valid application after this long idle
  bool stay_in_bootloader = false;  // this boot follows Reboot{bootloader} or DFU_DETACH
};

BoardResult<protocol::RebootMode> run_board(const LinuxBoardOptions& options);

// One line on stdout, prefixed "tetrapulse-board: [monotonic seconds] " (tests read these).
void board_log(const std::string& line);

}  // namespace tetrapulse::linux_board
