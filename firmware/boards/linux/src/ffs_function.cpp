// FunctionFS user-space function (Documentation/usb/functionfs.rst, linux/usb/functionfs.h).
#include "tetrapulse/linux_board/ffs_function.hpp"

#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

#include "tetrapulse/linux_board/monotonic_clock.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace tp = protocol;

void put_u32(std::vector<uint8_t>& v, uint32_t x) {
  for (int i = 0; i < 4; ++i) v.push_back(static_cast<uint8_t>(x >> (8 * i)));
}
void patch_u32(std::vector<uint8_t>& v, size_t at, uint32_t x) {
  for (int i = 0; i < 4; ++i) v[at + static_cast<size_t>(i)] = static_cast<uint8_t>(x >> (8 * i));
}

// The number of descriptors in `bytes`, setting bulk endpoints' wMaxPacketSize to `packet`.
uint32_t count_and_size(std::vector<uint8_t>& bytes, uint16_t packet) {
  uint32_t count = 0;
  for (size_t at = 0; at + 1 < bytes.size() && bytes[at] >= 2; at += bytes[at]) {
    ++count;
    if (bytes[at + 1] == tp::kUsbDescriptorEndpoint && bytes[at] >= 6) {
      bytes[at + 4] = static_cast<uint8_t>(packet & 0xFF);
      bytes[at + 5] = static_cast<uint8_t>(packet >> 8);
    }
  }
  return count;
}

bool write_all(int fd, const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

const char* event_name(uint8_t type) {
  switch (type) {
    case FUNCTIONFS_BIND: return "BIND";
    case FUNCTIONFS_UNBIND: return "UNBIND";
    case FUNCTIONFS_ENABLE: return "ENABLE";
    case FUNCTIONFS_DISABLE: return "DISABLE";
    case FUNCTIONFS_SETUP: return "SETUP";
    case FUNCTIONFS_SUSPEND: return "SUSPEND";
    case FUNCTIONFS_RESUME: return "RESUME";
    default: return "UNKNOWN";
  }
}

}  // namespace

struct FfsFunction::Bulk {
  int out = -1;
  int in = -1;
  int event = -1;
  std::mutex mutex;
  std::condition_variable to_write;
  std::condition_variable written;
  size_t unwritten = 0;  // queued or being written
  std::deque<BulkTransfer> received;
  std::deque<std::vector<uint8_t>> outgoing;

  // Reads fail while the function is disabled or unbound; FunctionFS then blocks the next
  // read until the endpoint is enabled again, so the loop simply retries.
  void read_loop() {
    std::vector<uint8_t> buffer(4096);
    for (;;) {
      const ssize_t n = ::read(out, buffer.data(), buffer.size());
      if (n < 0) {
        if (errno != EINTR) usleep(10000);
        continue;
      }
      if (n == 0) continue;
      {
        std::lock_guard<std::mutex> lock(mutex);
        received.push_back({std::vector<uint8_t>(buffer.begin(), buffer.begin() + n), monotonic_ns()});
      }
      const uint64_t one = 1;
      if (::write(event, &one, sizeof(one)) < 0) continue;
    }
  }
  void write_loop() {
    for (;;) {
      std::vector<uint8_t> transfer;
      {
        std::unique_lock<std::mutex> lock(mutex);
        to_write.wait(lock, [&] { return !outgoing.empty(); });
        transfer = std::move(outgoing.front());
        outgoing.pop_front();
      }
      // A transfer the host never collects (it went away) is dropped with the error.
      static_cast<void>(write_all(in, transfer.data(), transfer.size()));
      {
        std::lock_guard<std::mutex> lock(mutex);
        --unwritten;
      }
      written.notify_all();
    }
  }
};

FfsBlobs ffs_blobs(const tp::UsbDeviceParams& params, const std::string& serial) {
  uint8_t built[tp::kUsbMaxConfigurationSize];
  const tp::Result<size_t> n = tp::build_usb_function_descriptors(params, built, sizeof(built));
  FfsBlobs blobs;
  std::vector<uint8_t> full(built, built + (n ? *n : 0));
  std::vector<uint8_t> high = full;
  const uint32_t full_count = count_and_size(full, tp::kUsbMaxPacketSize);
  const uint32_t high_count = count_and_size(high, 512);  // USB 2.0 §5.8.3: high-speed bulk
  std::vector<uint8_t>& d = blobs.descriptors;
  put_u32(d, FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
  put_u32(d, 0);
  put_u32(d, FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC);
  put_u32(d, full_count);
  put_u32(d, high_count);
  d.insert(d.end(), full.begin(), full.end());
  d.insert(d.end(), high.begin(), high.end());
  patch_u32(d, 4, static_cast<uint32_t>(d.size()));

  // Indices as protocol/usb_device.hpp numbers them; the interface strings are the ones used.
  const std::array<std::string, 4> strings = {tp::kUsbManufacturerString, tp::kUsbProductString, serial,
                                              tp::kUsbDfuInterfaceString};
  std::vector<uint8_t>& s = blobs.strings;
  put_u32(s, FUNCTIONFS_STRINGS_MAGIC);
  put_u32(s, 0);
  put_u32(s, static_cast<uint32_t>(strings.size()));
  put_u32(s, 1);  // one language
  s.push_back(static_cast<uint8_t>(tp::kUsbLanguageEnglishUs & 0xFF));
  s.push_back(static_cast<uint8_t>(tp::kUsbLanguageEnglishUs >> 8));
  for (const std::string& text : strings) {
    s.insert(s.end(), text.begin(), text.end());
    s.push_back(0);
  }
  patch_u32(s, 4, static_cast<uint32_t>(s.size()));
  return blobs;
}

BoardResult<std::unique_ptr<FfsFunction>> FfsFunction::open(const std::string& mount_dir,
                                                             const tp::UsbDeviceParams& params,
                                                             const std::string& serial) {
  const std::string ep0 = mount_dir + "/ep0";
  const auto failed = [](std::string where, std::string message) {
    return board_error(BoardErrorKind::kUsbGadget, std::move(where), std::move(message));
  };
  std::unique_ptr<FfsFunction> f(new FfsFunction());
  f->ep0_ = ::open(ep0.c_str(), O_RDWR | O_CLOEXEC);
  if (f->ep0_ < 0) return failed(ep0, std::strerror(errno));
  const FfsBlobs blobs = ffs_blobs(params, serial);
  if (!write_all(f->ep0_, blobs.descriptors.data(), blobs.descriptors.size())) {
    const char* hint = params.dfu_functional_descriptor ? " (a kernel before 6.x refuses the DFU functional descriptor)" : "";
    return failed(ep0, std::string("the kernel refused the descriptors: ") + std::strerror(errno) + hint);
  }
  if (!write_all(f->ep0_, blobs.strings.data(), blobs.strings.size())) {
    return failed(ep0, std::string("the kernel refused the strings: ") + std::strerror(errno));
  }
  f->bulk_event_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (f->bulk_event_ < 0) return failed("eventfd", std::strerror(errno));
  if (params.mode != tp::UsbMode::kApplication) return f;
  auto bulk = std::make_shared<Bulk>();
  bulk->event = f->bulk_event_;
  // FunctionFS names endpoint files by descriptor order: ep1 bulk OUT, ep2 bulk IN.
  bulk->out = ::open((mount_dir + "/ep1").c_str(), O_RDWR | O_CLOEXEC);
  bulk->in = ::open((mount_dir + "/ep2").c_str(), O_RDWR | O_CLOEXEC);
  if (bulk->out < 0 || bulk->in < 0) return failed(mount_dir + "/ep1, ep2", std::strerror(errno));
  std::thread([bulk] { bulk->read_loop(); }).detach();
  std::thread([bulk] { bulk->write_loop(); }).detach();
  f->bulk_ = std::move(bulk);
  return f;
}

FfsFunction::~FfsFunction() {
  // The endpoint threads keep their files; ep0 and the event go (the gadget unbinds).
  if (ep0_ >= 0) ::close(ep0_);
}

void FfsFunction::set_function(uint8_t number, fw::UsbFunction& function) {
  if (number < 2) functions_[number] = &function;
}

void FfsFunction::reset_functions() {
  for (fw::UsbFunction* f : functions_) {
    if (f != nullptr) f->bus_reset();
  }
}

std::vector<const char*> FfsFunction::handle_ep0() {
  std::vector<const char*> seen;
  std::array<usb_functionfs_event, 4> events{};
  const ssize_t n = ::read(ep0_, events.data(), sizeof(events));
  if (n <= 0) return seen;
  for (size_t i = 0; i < static_cast<size_t>(n) / sizeof(usb_functionfs_event); ++i) {
    const usb_functionfs_event& e = events[i];
    switch (e.type) {
      case FUNCTIONFS_SETUP: {
        fw::UsbSetup setup;
        setup.request_type = e.u.setup.bRequestType;
        setup.request = e.u.setup.bRequest;
        setup.value = le16toh(e.u.setup.wValue);
        setup.index = le16toh(e.u.setup.wIndex);
        setup.length = le16toh(e.u.setup.wLength);
        answer(setup);
        continue;
      }
      case FUNCTIONFS_ENABLE:
        enabled_ = true;
        reset_functions();  // a new configuration: every function starts afresh
        break;
      case FUNCTIONFS_DISABLE:
      case FUNCTIONFS_UNBIND:
        // A USB reset, an unplug or an unbound gadget: what a bus reset means to a function.
        enabled_ = false;
        reset_functions();
        break;
      default:
        break;
    }
    seen.push_back(event_name(e.type));
  }
  return seen;
}

void FfsFunction::answer(const fw::UsbSetup& setup) {
  last_request_ns_ = monotonic_ns();
  const bool in = setup.device_to_host();
  fw::UsbFunction* function =
      setup.recipient() == fw::UsbRecipient::kInterface && (setup.index & 0xFF) < 2 ? functions_[setup.index & 0xFF]
                                                                                       : nullptr;
  const fw::UsbControlReply reply =
      function != nullptr ? function->setup(setup, scratch_, sizeof(scratch_)) : fw::UsbControlReply::stall();
  uint8_t none = 0;
  switch (reply.kind) {
    case fw::UsbControlReply::Kind::kSend: {
      const size_t size = reply.size < setup.length ? reply.size : setup.length;
      if (::write(ep0_, reply.data, size) >= 0) function->status_complete(setup);
      return;
    }
    case fw::UsbControlReply::Kind::kReceive: {
      const size_t room = setup.length < reply.size ? setup.length : reply.size;
      const ssize_t got = ::read(ep0_, reply.buffer, room);
      if (got < 0) return;
      // FunctionFS has already acknowledged the data stage; a refusal shows in the state.
      if (function->data_out(setup, tp::ByteView{reply.buffer, static_cast<size_t>(got)})) {
        function->status_complete(setup);
      }
      return;
    }
    case fw::UsbControlReply::Kind::kAccept:
      if (::read(ep0_, &none, 0) >= 0) function->status_complete(setup);
      return;
    case fw::UsbControlReply::Kind::kStall:
      break;
  }
  // FunctionFS stalls a request when it is answered in the wrong direction; that is
  // the stall, so the call fails by design.
  const ssize_t stalled = in ? ::read(ep0_, &none, 0) : ::write(ep0_, &none, 0);
  static_cast<void>(stalled);
}

std::vector<BulkTransfer> FfsFunction::take_bulk() {
  uint64_t count = 0;
  static_cast<void>(::read(bulk_event_, &count, sizeof(count)));
  std::vector<BulkTransfer> out;
  if (!bulk_) return out;
  std::lock_guard<std::mutex> lock(bulk_->mutex);
  out.assign(std::make_move_iterator(bulk_->received.begin()), std::make_move_iterator(bulk_->received.end()));
  bulk_->received.clear();
  return out;
}

void FfsFunction::drain(int timeout_ms) {
  if (!bulk_) return;
  std::unique_lock<std::mutex> lock(bulk_->mutex);
  bulk_->written.wait_for(lock, std::chrono::milliseconds(timeout_ms), [&] { return bulk_->unwritten == 0; });
}

tp::Status FfsFunction::do_send_bulk(tp::ByteView transfer) {
  if (!bulk_) return tp::Error::kInvalidState;
  {
    std::lock_guard<std::mutex> lock(bulk_->mutex);
    if (bulk_->outgoing.size() >= 16) return tp::Error::kBusy;
    bulk_->outgoing.emplace_back(transfer.begin(), transfer.end());
    ++bulk_->unwritten;
  }
  bulk_->to_write.notify_one();
  return {};
}

}  // namespace tetrapulse::linux_board
