#pragma once
// The two things a boot can run after boot selection (linux_board.cpp), and what both use.
#include <memory>

#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/linux_board/ffs_function.hpp"
#include "tetrapulse/linux_board/file_flash.hpp"
#include "tetrapulse/linux_board/linux_board.hpp"
#include "tetrapulse/linux_board/usb_gadget.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::linux_board {

// Each returns when the board resets, with the mode the reset asks for (run_board()).
BoardResult<protocol::RebootMode> run_application(const LinuxBoardOptions& options, FileFlash& flash,
                                                  const fw::BootChoice& choice);
BoardResult<protocol::RebootMode> run_dfu_mode(const LinuxBoardOptions& options, FileFlash& flash);

// The USB device parameters of this board in `mode` (bcdDevice from the version).
protocol::UsbDeviceParams linux_usb_params(protocol::UsbMode mode, uint32_t fw_version);

// Creates `gadget` as options.usb_gadget says, for `params` (its mode and bcdDevice), and
// opens its FunctionFS function (removing the gadget again when that fails). The caller
// sets the functions behind its interfaces, then binds the gadget.
BoardResult<std::unique_ptr<FfsFunction>> open_usb_function(UsbGadget& gadget, const LinuxBoardOptions& options,
                                                             const protocol::UsbDeviceParams& params);

}  // namespace tetrapulse::linux_board
