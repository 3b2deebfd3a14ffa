#include "usb_device.hpp"

#include <poll.h>

#include <chrono>
#include <thread>

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/protocol/dfu.hpp"

namespace tetrapulse::host::usb {

using protocol::UsbMode;

std::string describe(int e) {
  switch (e) {
    case LIBUSB_ERROR_ACCESS: return "permission denied (udev rule for 1209:0001/0002?)";
    case LIBUSB_ERROR_NO_DEVICE: return "the device went away";
    case LIBUSB_ERROR_BUSY: return "busy: another program has claimed it";
    case LIBUSB_ERROR_TIMEOUT: return "timed out";
    case LIBUSB_ERROR_PIPE: return "the device stalled the request";
    case LIBUSB_ERROR_OVERFLOW: return "the device sent more than asked for";
    case LIBUSB_ERROR_NOT_FOUND: return "not found";
    default: return libusb_strerror(static_cast<libusb_error>(e));
  }
}

HostResult<Context> make_context() {
  libusb_context* c = nullptr;
  const int r = libusb_init(&c);
  if (r != 0) return host_error(HostErrorKind::kOpenFailed, "usb", "cannot start libusb: " + describe(r));
  return Context(c);
}

UsbBoardHandle::~UsbBoardHandle() {
  for (uint8_t i : claimed_) libusb_release_interface(handle_, i);
  libusb_close(handle_);
}

HostResult<void> UsbBoardHandle::claim(uint8_t interface_number, const std::string& device_name) {
  for (uint8_t i : claimed_) {
    if (i == interface_number) return {};
  }
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  const int r = libusb_claim_interface(handle_, interface_number);
  if (r != 0) {
    return host_error(HostErrorKind::kOpenFailed, device_name,
                      fmt::format("cannot claim interface {}: {}", interface_number, describe(r)));
  }
  claimed_.push_back(interface_number);
  return {};
}

namespace {

std::string string_descriptor(libusb_device_handle* h, uint8_t index) {
  if (index == 0) return {};
  unsigned char text[256];
  const int n = libusb_get_string_descriptor_ascii(h, index, text, sizeof(text));
  return n > 0 ? std::string(reinterpret_cast<const char*>(text), static_cast<size_t>(n)) : std::string();
}

std::string port_path(libusb_device* dev) {
  uint8_t ports[8];
  const int n = libusb_get_port_numbers(dev, ports, sizeof(ports));
  std::string path = std::to_string(libusb_get_bus_number(dev));
  for (int i = 0; i < n; ++i) path += (i == 0 ? "-" : ".") + std::to_string(ports[i]);
  return path;
}

// Checks one device with our VID:PID; returns its listing and, when it is a board, its handle.
std::pair<UsbBoardListing, libusb_device_handle*> inspect(libusb_device* dev, const libusb_device_descriptor& d,
                                                          UsbLayout* layout) {
  UsbBoardListing l;
  l.mode = d.idProduct == protocol::kUsbProductIdBootloader ? UsbMode::kBootloader : UsbMode::kApplication;
  l.bus = libusb_get_bus_number(dev);
  l.address = libusb_get_device_address(dev);
  l.port = port_path(dev);
  libusb_device_handle* h = nullptr;
  const int opened = libusb_open(dev, &h);
  if (opened != 0) {
    l.problem = "cannot open: " + describe(opened);
    return {l, nullptr};
  }
  auto reject = [&](std::string why) {
    l.problem = std::move(why);
    libusb_close(h);
    return std::make_pair(l, static_cast<libusb_device_handle*>(nullptr));
  };
  l.serial = string_descriptor(h, d.iSerialNumber);
  const std::string product = string_descriptor(h, d.iProduct);
  if (product != protocol::kUsbProductString) return reject(fmt::format("product string is '{}', not a tetrapulse board", product));
  uint8_t raw[512];
  const int size = libusb_get_descriptor(h, LIBUSB_DT_CONFIG, 0, raw, sizeof(raw));
  if (size < 0) return reject("cannot read the configuration descriptor: " + describe(size));
  auto parsed = parse_usb_layout(protocol::ByteView{raw, static_cast<size_t>(size)});
  if (!parsed) return reject(parsed.error().message);
  *layout = *parsed;
  if (l.mode == UsbMode::kBootloader) {
    if (!layout->dfu || !layout->dfu->dfu_mode || layout->messages) return reject("not a DFU-mode interface");
    return {l, h};
  }
  if (!layout->messages) return reject("no message interface FF/54/01 with two bulk endpoints");
  uint8_t answer[64];
  const int got = libusb_control_transfer(h, protocol::kUsbVendorRequestTypeIn,
                                          static_cast<uint8_t>(protocol::UsbVendorRequest::kProtocolInfo), 0,
                                          layout->messages->number, answer, sizeof(answer), 1000);
  if (got < 0) return reject("PROTOCOL_INFO: " + describe(got));
  const auto info = protocol::decode_usb_protocol_info(protocol::ByteView{answer, static_cast<size_t>(got)});
  if (!info) return reject(fmt::format("PROTOCOL_INFO answer of {} bytes", got));
  if (info->protocol_version != protocol::kProtocolVersion) {
    return reject(fmt::format("speaks protocol version {}, not {}", info->protocol_version, protocol::kProtocolVersion));
  }
  l.protocol_info = *info;
  return {l, h};
}

template <class Visit>
HostResult<void> for_each_candidate(libusb_context* ctx, Visit&& visit) {
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  if (n < 0) return host_error(HostErrorKind::kOpenFailed, "usb", "cannot list USB devices: " + describe(static_cast<int>(n)));
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor d{};
    if (libusb_get_device_descriptor(list[i], &d) != 0 || d.idVendor != protocol::kUsbVendorId) continue;
    if (d.idProduct != protocol::kUsbProductIdApplication && d.idProduct != protocol::kUsbProductIdBootloader) continue;
    if (!visit(list[i], d)) break;
  }
  libusb_free_device_list(list, 1);
  return {};
}

const char* mode_name(UsbMode mode) { return mode == UsbMode::kBootloader ? "bootloader (DFU)" : "application"; }

}  // namespace

}  // namespace tetrapulse::host::usb

namespace tetrapulse::host {

std::string usb_link_name(const std::string& serial) { return serial.empty() ? "usb" : "usb:" + serial; }

HostResult<std::vector<UsbBoardListing>> list_usb_boards() {
  auto ctx = usb::make_context();
  if (!ctx) return tl::unexpected(ctx.error());
  std::vector<UsbBoardListing> out;
  auto listed = usb::for_each_candidate(ctx->get(), [&](libusb_device* dev, const libusb_device_descriptor& d) {
    UsbLayout layout;
    auto [listing, handle] = usb::inspect(dev, d, &layout);
    if (handle != nullptr) libusb_close(handle);
    out.push_back(listing);
    return true;
  });
  if (!listed) return tl::unexpected(listed.error());
  return out;
}

}  // namespace tetrapulse::host

namespace tetrapulse::host::usb {

HostResult<std::unique_ptr<UsbBoardHandle>> open_board(const std::string& serial, UsbMode mode) {
  const std::string name = usb_link_name(serial);
  auto ctx = make_context();
  if (!ctx) return tl::unexpected(ctx.error());
  libusb_device_handle* found = nullptr;
  UsbBoardListing found_listing;
  UsbLayout found_layout;
  std::vector<std::string> boards, problems;
  auto listed = for_each_candidate(ctx->get(), [&](libusb_device* dev, const libusb_device_descriptor& d) {
    UsbLayout layout;
    auto [listing, handle] = inspect(dev, d, &layout);
    if (handle == nullptr) {
      problems.push_back(fmt::format("{} at {}: {}", listing.serial.empty() ? "a device" : listing.serial, listing.port,
                                     listing.problem));
      return true;
    }
    if (listing.mode != mode || (!serial.empty() && listing.serial != serial)) {
      libusb_close(handle);
      return true;
    }
    boards.push_back(listing.serial);
    if (found != nullptr) {
      libusb_close(handle);
      return true;
    }
    found = handle;
    found_listing = listing;
    found_layout = layout;
    return true;
  });
  if (!listed) return tl::unexpected(listed.error());
  if (found != nullptr && boards.size() > 1) libusb_close(found);
  if (boards.size() > 1) {
    std::string names;
    for (const auto& b : boards) names += (names.empty() ? "" : ", ") + b;
    return host_error(HostErrorKind::kNotFound, name,
                      fmt::format("{} boards in {} mode ({}): say which with --usb SERIAL", boards.size(), mode_name(mode), names));
  }
  if (found == nullptr) {
    std::string why = problems.empty() ? "" : " (" + problems.front() + ")";
    return host_error(HostErrorKind::kNotFound, name, fmt::format("no board in {} mode{}", mode_name(mode), why));
  }
  // The handle keeps its context alive for as long as it is open.
  return std::make_unique<UsbBoardHandle>(std::move(*ctx), found, found_listing, found_layout);
}

namespace {

// Wakes a waiting host when a device with our vendor id arrives, where libusb has hotplug.
class ArrivalWatcher {
 public:
  ArrivalWatcher() {
    if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) == 0) return;
    auto ctx = make_context();
    if (!ctx) return;
    context_ = std::move(*ctx);
    if (libusb_hotplug_register_callback(context_.get(), LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, LIBUSB_HOTPLUG_NO_FLAGS,
                                         protocol::kUsbVendorId, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
                                         &ArrivalWatcher::arrived, this, &callback_) != LIBUSB_SUCCESS) {
      context_.reset();
    }
  }
  ~ArrivalWatcher() {
    if (context_) libusb_hotplug_deregister_callback(context_.get(), callback_);
  }
  // Waits up to `ms` or until an arrival.
  void wait(int ms) {
    if (!context_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      return;
    }
    const int64_t until = monotonic_now_ns() + int64_t{ms} * 1'000'000;
    arrived_ = false;
    while (!arrived_ && monotonic_now_ns() < until) {
      timeval tv{0, 20'000};
      libusb_handle_events_timeout_completed(context_.get(), &tv, nullptr);
    }
  }

 private:
  static int LIBUSB_CALL arrived(libusb_context*, libusb_device*, libusb_hotplug_event, void* self) {
    static_cast<ArrivalWatcher*>(self)->arrived_ = true;
    return 0;
  }
  Context context_;
  libusb_hotplug_callback_handle callback_ = 0;
  bool arrived_ = false;
};

}  // namespace

HostResult<std::unique_ptr<UsbBoardHandle>> wait_for_board(const std::string& serial, UsbMode mode, int timeout_ms) {
  const int64_t deadline = monotonic_now_ns() + int64_t{timeout_ms} * 1'000'000;
  ArrivalWatcher watcher;
  for (;;) {
    auto board = open_board(serial, mode);
    if (board || board.error().kind != HostErrorKind::kNotFound || monotonic_now_ns() >= deadline) {
      if (!board && board.error().kind == HostErrorKind::kNotFound) {
        HostError e = board.error();
        e.kind = HostErrorKind::kDisconnected;
        e.message = fmt::format("{} within {} ms", e.message, timeout_ms);
        return tl::unexpected(e);
      }
      return board;
    }
    watcher.wait(100);
  }
}

}  // namespace tetrapulse::host::usb
