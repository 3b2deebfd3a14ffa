#pragma once
// The two things a boot can run, after boot selection (linux_board.cpp).
#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/linux_board/file_flash.hpp"
#include "tetrapulse/linux_board/linux_board.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::linux_board {

// Each returns when the board resets, with the mode the reset asks for (run_board()).
BoardResult<protocol::RebootMode> run_application(const LinuxBoardOptions& options, FileFlash& flash,
                                                  const fw::BootChoice& choice);
BoardResult<protocol::RebootMode> run_dfu_mode(const LinuxBoardOptions& options, FileFlash& flash);

// The USB device parameters of this board in `mode` (bcdDevice from the version).
protocol::UsbDeviceParams linux_usb_params(protocol::UsbMode mode, uint32_t fw_version);

}  // namespace tetrapulse::linux_board
