#pragma once
// Firmware download to a board over USB DFU 1.1 (protocol/SPEC.md §5.6), what
// `dfu-util -D image -R` does: a board running its application gets DFU_DETACH on its
// run-time interface, leaves the bus and comes back in its bootloader (PID 0x0002, same
// serial number); the image goes down with dfu_download(); a USB reset then starts the
// new firmware. A board already in its bootloader is downloaded to directly.
#include <chrono>
#include <optional>
#include <string>

#include "tetrapulse/host/dfu_download.hpp"
#include "tetrapulse/host/flash_progress.hpp"
#include "tetrapulse/host/host_error.hpp"

namespace tetrapulse::host {

struct UsbDfuOptions {
  // wTransferSize for a device without a DFU functional descriptor (Linux 6.1 FunctionFS
  // gadgets cannot send one; dfu-util then needs -t). Ignored when the device has one.
  size_t transfer_size = 1024;
  std::chrono::milliseconds reenumeration_timeout{10000};  // after DETACH, beyond wDetachTimeOut
  bool reset_after = true;  // USB reset after manifestation (dfu-util -R)
  FlashProgressCallback progress;
  const CancelFlag* cancel = nullptr;
};

struct UsbDfuReport {
  std::string serial;
  bool detached = false;            // the board was running its application
  bool functional_descriptor = false;
  size_t transfer_size = 0;
  DfuDownloadReport download;
};

HostResult<UsbDfuReport> usb_dfu_flash(const std::string& serial, protocol::ByteView image, const UsbDfuOptions& options);

}  // namespace tetrapulse::host
