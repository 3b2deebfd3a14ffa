#pragma once
// libusb plumbing shared by UsbLink, discovery and DFU (private to the host library).
// Each UsbBoardHandle owns its own libusb context: a context enumerates the bus when it
// starts, and without udev running (the test VM, minimal systems) libusb's device list
// would not see a board that re-enumerates later, so every (re)open starts afresh.
#include <libusb.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/host/usb_discovery.hpp"
#include "tetrapulse/host/usb_layout.hpp"

namespace tetrapulse::host::usb {

struct ContextDeleter {
  void operator()(libusb_context* c) const { libusb_exit(c); }
};
using Context = std::unique_ptr<libusb_context, ContextDeleter>;

HostResult<Context> make_context();

// "LIBUSB_ERROR_ACCESS" -> "permission denied" etc.
std::string describe(int libusb_error);

// An open board: its context, handle, layout and identity.
class UsbBoardHandle {
 public:
  UsbBoardHandle(Context context, libusb_device_handle* handle, UsbBoardListing listing, UsbLayout layout)
      : context_(std::move(context)), handle_(handle), listing_(std::move(listing)), layout_(layout) {}
  ~UsbBoardHandle();
  UsbBoardHandle(const UsbBoardHandle&) = delete;
  UsbBoardHandle& operator=(const UsbBoardHandle&) = delete;

  libusb_device_handle* get() const { return handle_; }
  const UsbBoardListing& listing() const { return listing_; }
  const UsbLayout& layout() const { return layout_; }
  // Claims `interface_number` once (released when the handle closes).
  HostResult<void> claim(uint8_t interface_number, const std::string& device_name);

 private:
  Context context_;
  libusb_device_handle* handle_;
  UsbBoardListing listing_;
  UsbLayout layout_;
  std::vector<uint8_t> claimed_;
};

// Opens the board with this serial in this mode ("" = the only one); kNotFound when there
// is none (or, for "", several: the message lists them).
HostResult<std::unique_ptr<UsbBoardHandle>> open_board(const std::string& serial, protocol::UsbMode mode);

// open_board, retried until `timeout_ms` passes: a board that is re-enumerating (DFU
// detach, reboot, a cable replugged). Wakes on libusb hotplug events where the platform
// has them and rescans every 100 ms in any case.
HostResult<std::unique_ptr<UsbBoardHandle>> wait_for_board(const std::string& serial, protocol::UsbMode mode,
                                                          int timeout_ms);

}  // namespace tetrapulse::host::usb
