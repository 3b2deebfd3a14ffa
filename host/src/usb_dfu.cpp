#include "tetrapulse/host/usb_dfu.hpp"

#include <chrono>
#include <thread>

#include <fmt/format.h>

#include "usb_device.hpp"

namespace tetrapulse::host {
namespace {

using protocol::DfuRequest;

constexpr unsigned kControlTimeoutMs = 5000;

class UsbDfuControl final : public DfuControl {
 public:
  UsbDfuControl(std::string name, libusb_device_handle* handle, uint8_t interface_number)
      : name_(std::move(name)), handle_(handle), interface_(interface_number) {}

  HostResult<void> detach(uint16_t timeout_ms) { return out(DfuRequest::kDetach, timeout_ms, nullptr, 0); }

 private:
  const std::string& do_name() const override { return name_; }
  HostResult<void> do_download(uint16_t block, protocol::ByteView data) override {
    return out(DfuRequest::kDownload, block, const_cast<uint8_t*>(data.data), static_cast<uint16_t>(data.size));
  }
  HostResult<protocol::DfuStatus> do_get_status() override {
    uint8_t answer[protocol::kDfuStatusSize];
    const int n = libusb_control_transfer(handle_, protocol::kDfuRequestTypeIn,
                                          static_cast<uint8_t>(DfuRequest::kGetStatus), 0, interface_, answer,
                                          sizeof(answer), kControlTimeoutMs);
    if (n < 0) return host_error(HostErrorKind::kIo, name_, "DFU_GETSTATUS: " + usb::describe(n));
    const auto status = protocol::decode_dfu_status(protocol::ByteView{answer, static_cast<size_t>(n)});
    if (!status) {
      return host_error(HostErrorKind::kMalformed, name_,
                        fmt::format("DFU_GETSTATUS answer of {} bytes: {}", n, protocol::error_name(status.error())));
    }
    return *status;
  }
  HostResult<void> do_clear_status() override { return out(DfuRequest::kClearStatus, 0, nullptr, 0); }
  HostResult<void> do_abort() override { return out(DfuRequest::kAbort, 0, nullptr, 0); }
  void do_wait_ms(uint32_t ms) override { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

  HostResult<void> out(DfuRequest request, uint16_t value, uint8_t* data, uint16_t size) {
    const int n = libusb_control_transfer(handle_, protocol::kDfuRequestTypeOut, static_cast<uint8_t>(request), value,
                                          interface_, data, size, kControlTimeoutMs);
    if (n < 0) return host_error(HostErrorKind::kIo, name_, fmt::format("DFU request {}: {}", static_cast<int>(request), usb::describe(n)));
    return {};
  }

  std::string name_;
  libusb_device_handle* handle_;
  uint8_t interface_;
};

// Whether the board with this serial number is still enumerated, in either mode (a new
// libusb context: it sees the bus as it is now).
bool on_the_bus(const std::string& serial) {
  for (const protocol::UsbMode mode : {protocol::UsbMode::kBootloader, protocol::UsbMode::kApplication}) {
    auto board = usb::open_board(serial, mode);
    if (board || board.error().kind != HostErrorKind::kNotFound) return true;
  }
  return false;
}

}  // namespace

HostResult<UsbDfuReport> usb_dfu_flash(const std::string& serial, protocol::ByteView image, const UsbDfuOptions& options) {
  UsbDfuReport report;
  std::string name = usb_link_name(serial);
  auto progress = [&](const char* stage, uint64_t done, uint64_t total) {
    if (options.progress) options.progress(FlashProgress{stage, done, total});
  };

  auto board = usb::open_board(serial, protocol::UsbMode::kBootloader);
  if (!board && board.error().kind == HostErrorKind::kNotFound) {
    // Not in its bootloader: detach the application.
    auto app = usb::open_board(serial, protocol::UsbMode::kApplication);
    if (!app) return tl::unexpected(app.error());
    report.serial = (*app)->listing().serial;
    name = usb_link_name(report.serial);
    const auto& dfu = (*app)->layout().dfu;
    if (!dfu || dfu->dfu_mode) return host_error(HostErrorKind::kNotFound, name, "has no DFU run-time interface");
    if (auto claimed = (*app)->claim(dfu->number, name); !claimed) return tl::unexpected(claimed.error());
    const uint16_t detach_ms = dfu->functional ? dfu->functional->detach_timeout_ms : 1000;
    const bool will_detach = !dfu->functional || (dfu->functional->attributes & protocol::kDfuWillDetach) != 0;
    progress("detach", 0, 1);
    UsbDfuControl runtime(name, (*app)->get(), dfu->number);
    if (auto detached = runtime.detach(detach_ms); !detached) {
      HostError e = detached.error();
      e.message = "DFU_DETACH: " + e.message;
      return tl::unexpected(e);
    }
    // bitWillDetach: the board leaves the bus by itself; otherwise the host resets it.
    if (!will_detach) libusb_reset_device((*app)->get());
    app->reset();
    report.detached = true;
    board = usb::wait_for_board(report.serial, protocol::UsbMode::kBootloader,
                                detach_ms + static_cast<int>(options.reenumeration_timeout.count()));
    if (!board) {
      HostError e = board.error();
      e.message = "after DFU_DETACH: " + e.message;
      return tl::unexpected(e);
    }
    progress("detach", 1, 1);
  }
  if (!board) return tl::unexpected(board.error());
  report.serial = (*board)->listing().serial;
  name = usb_link_name(report.serial);
  const UsbDfuInterface& dfu = *(*board)->layout().dfu;
  if (auto claimed = (*board)->claim(dfu.number, name); !claimed) return tl::unexpected(claimed.error());
  report.functional_descriptor = dfu.functional.has_value();
  report.transfer_size = dfu.functional ? dfu.functional->transfer_size : options.transfer_size;

  UsbDfuControl control(name, (*board)->get(), dfu.number);
  DfuDownloadOptions download;
  download.transfer_size = report.transfer_size;
  download.progress = options.progress;
  download.cancel = options.cancel;
  auto done = dfu_download(control, image, download);
  if (!done && done.error().kind == HostErrorKind::kIo && !on_the_bus(report.serial)) {
    // The transfer failed because the board left the bus (unplugged, reset, its gadget
    // unbound): say so, and that its bootloader keeps the old image.
    HostError e = done.error();
    e.kind = HostErrorKind::kDisconnected;
    e.message = "the board left the bus during the download (" + e.message +
                "); it keeps the firmware it had: flash again once it is back";
    return tl::unexpected(e);
  }
  if (!done) return tl::unexpected(done.error());
  report.download = *done;
  if (options.reset_after || done->needs_reset) {
    // The bootloader starts the new firmware on reset; the device leaves the bus meanwhile,
    // so "not found" or "no device" answers are what success looks like.
    libusb_reset_device((*board)->get());
  }
  return report;
}

}  // namespace tetrapulse::host
