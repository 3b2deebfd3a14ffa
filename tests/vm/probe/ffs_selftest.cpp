// ffs_selftest: a minimal FunctionFS USB function that proves the test VM's
// gadget stack (dummy_hcd, libcomposite, usb_f_fs). It writes its descriptors
// and strings to ep0 of a mounted FunctionFS, then echoes every bulk OUT
// transfer back on bulk IN. With --dfu-runtime it adds a DFU run-time
// interface (class 0xFE, subclass 1, protocol 1) with its functional
// descriptor (type 0x21) and answers DFU_GETSTATUS / DFU_GETSTATE.
//
// usage: ffs_selftest [--dfu-runtime] FFS_DIR
// The gadget around it (configfs, VID/PID, UDC) is set up by the test script;
// it must write UDC only after this program printed "descriptors accepted".

#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr uint8_t kDfuFunctionalType = 0x21;
constexpr uint8_t kDfuGetStatus = 0x03;
constexpr uint8_t kDfuGetState = 0x05;
constexpr uint8_t kDfuDetach = 0x00;

// Little-endian descriptor bytes, as FunctionFS expects them on every host.
class DescriptorBytes {
 public:
  void U8(uint8_t v) { bytes_.push_back(v); }
  void U8s(std::initializer_list<uint8_t> vs) { bytes_.insert(bytes_.end(), vs.begin(), vs.end()); }
  void U16(uint16_t v) {
    U8(static_cast<uint8_t>(v & 0xFF));
    U8(static_cast<uint8_t>(v >> 8));
  }
  void U32(uint32_t v) {
    U16(static_cast<uint16_t>(v & 0xFFFF));
    U16(static_cast<uint16_t>(v >> 16));
  }
  void Append(const std::vector<uint8_t>& other) { bytes_.insert(bytes_.end(), other.begin(), other.end()); }
  void PatchU32(size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes_[at + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

struct SpeedDescriptors {
  std::vector<uint8_t> bytes;
  uint32_t count = 0;
};

// One speed's descriptors: the echo interface with a bulk OUT and a bulk IN
// endpoint (the UDC may renumber them), then optionally the DFU run-time interface.
SpeedDescriptors DescriptorsForSpeed(uint16_t max_packet, bool dfu_runtime) {
  DescriptorBytes d;
  uint32_t count = 0;
  // Interface 0: vendor specific, two endpoints, string 1.
  d.U8s({USB_DT_INTERFACE_SIZE, USB_DT_INTERFACE, 0, 0, 2, USB_CLASS_VENDOR_SPEC, 0, 0, 1});
  ++count;
  for (const uint8_t address : {uint8_t{1 | USB_DIR_OUT}, uint8_t{2 | USB_DIR_IN}}) {
    d.U8s({USB_DT_ENDPOINT_SIZE, USB_DT_ENDPOINT, address, USB_ENDPOINT_XFER_BULK});
    d.U16(max_packet);
    d.U8(0);  // bInterval
    ++count;
  }
  if (dfu_runtime) {
    // Interface 1: DFU run-time (DFU 1.1, section 4.1), no endpoints, string 2.
    d.U8s({USB_DT_INTERFACE_SIZE, USB_DT_INTERFACE, 1, 0, 0, USB_CLASS_APP_SPEC, 1, 1, 2});
    ++count;
    // Functional descriptor: will detach, manifestation tolerant, can download
    // (bits 3, 2, 0); detach timeout 1000 ms, transfer size 1024, DFU version 1.1.
    d.U8s({9, kDfuFunctionalType, 0x0D});
    d.U16(1000);
    d.U16(1024);
    d.U16(0x0110);
    ++count;
  }
  return {d.bytes(), count};
}

std::vector<uint8_t> DescriptorBlob(bool dfu_runtime) {
  const SpeedDescriptors full = DescriptorsForSpeed(64, dfu_runtime);
  const SpeedDescriptors high = DescriptorsForSpeed(512, dfu_runtime);
  DescriptorBytes blob;
  blob.U32(FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
  blob.U32(0);  // total length, patched below
  blob.U32(FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC);
  blob.U32(full.count);
  blob.U32(high.count);
  blob.Append(full.bytes);
  blob.Append(high.bytes);
  blob.PatchU32(4, static_cast<uint32_t>(blob.bytes().size()));
  return blob.bytes();
}

std::vector<uint8_t> StringBlob(bool dfu_runtime) {
  std::vector<std::string> strings = {"tetrapulse vm echo"};
  if (dfu_runtime) strings.emplace_back("tetrapulse vm dfu runtime");
  DescriptorBytes blob;
  blob.U32(FUNCTIONFS_STRINGS_MAGIC);
  blob.U32(0);  // total length, patched below
  blob.U32(static_cast<uint32_t>(strings.size()));
  blob.U32(1);  // one language
  blob.U16(0x0409);
  for (const std::string& s : strings) {
    for (char c : s) blob.U8(static_cast<uint8_t>(c));
    blob.U8(0);
  }
  blob.PatchU32(4, static_cast<uint32_t>(blob.bytes().size()));
  return blob.bytes();
}

bool WriteAll(int fd, const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

// Echoes bulk OUT transfers on bulk IN. A transfer ends with a short packet
// (or a zero-length one the host adds after a multiple of the packet size).
// Reads fail while the function is disabled (ESHUTDOWN); it then retries.
[[noreturn]] void EchoLoop(const std::string& dir) {
  const int out = open((dir + "/ep1").c_str(), O_RDWR);
  const int in = open((dir + "/ep2").c_str(), O_RDWR);
  if (out < 0 || in < 0) {
    std::fprintf(stderr, "ffs_selftest: cannot open %s/ep1 and ep2: %s\n", dir.c_str(), std::strerror(errno));
    _exit(1);
  }
  std::vector<uint8_t> buffer(65536);
  for (;;) {
    const ssize_t n = read(out, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno != EINTR) usleep(20000);
      continue;
    }
    if (n == 0) continue;
    if (!WriteAll(in, buffer.data(), static_cast<size_t>(n))) {
      std::fprintf(stderr, "ffs_selftest: echo of %zd bytes failed: %s\n", n, std::strerror(errno));
    }
  }
}

const char* EventName(uint8_t type) {
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

// Answers a control request routed to this function. FunctionFS stalls when
// the program reads for an IN request or writes for an OUT one.
void AnswerSetup(int ep0, const usb_ctrlrequest& setup, bool dfu_runtime) {
  const bool in = (setup.bRequestType & USB_DIR_IN) != 0;
  const bool dfu_class = dfu_runtime && (setup.bRequestType & USB_TYPE_MASK) == USB_TYPE_CLASS;
  std::printf("ffs_selftest: setup type 0x%02x request 0x%02x length %u\n", setup.bRequestType, setup.bRequest,
              static_cast<unsigned>(setup.wLength));
  if (dfu_class && in && setup.bRequest == kDfuGetStatus) {
    // bStatus OK, bwPollTimeout 0, bState appIDLE, iString 0.
    const std::array<uint8_t, 6> status = {0, 0, 0, 0, 0, 0};
    if (write(ep0, status.data(), std::min<size_t>(status.size(), setup.wLength)) < 0) {
      std::perror("ffs_selftest: DFU_GETSTATUS reply");
    }
    return;
  }
  if (dfu_class && in && setup.bRequest == kDfuGetState) {
    const uint8_t state = 0;  // appIDLE
    if (write(ep0, &state, 1) < 0) std::perror("ffs_selftest: DFU_GETSTATE reply");
    return;
  }
  if (dfu_class && !in && setup.bRequest == kDfuDetach) {
    std::printf("ffs_selftest: DFU_DETACH received\n");
    if (read(ep0, nullptr, 0) < 0) std::perror("ffs_selftest: DFU_DETACH status");
    return;
  }
  uint8_t none = 0;
  const ssize_t ignored = in ? read(ep0, &none, 0) : write(ep0, &none, 0);
  static_cast<void>(ignored);  // fails with EL2HLT by design: that is the stall
}

}  // namespace

int main(int argc, char** argv) {
  bool dfu_runtime = false;
  std::string dir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--dfu-runtime") {
      dfu_runtime = true;
    } else if (dir.empty() && !arg.empty() && arg[0] != '-') {
      dir = arg;
    } else {
      std::fprintf(stderr, "usage: ffs_selftest [--dfu-runtime] FFS_DIR\n");
      return 2;
    }
  }
  if (dir.empty()) {
    std::fprintf(stderr, "usage: ffs_selftest [--dfu-runtime] FFS_DIR\n");
    return 2;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  const int ep0 = open((dir + "/ep0").c_str(), O_RDWR);
  if (ep0 < 0) {
    std::fprintf(stderr, "ffs_selftest: cannot open %s/ep0: %s\n", dir.c_str(), std::strerror(errno));
    return 1;
  }
  const std::vector<uint8_t> descriptors = DescriptorBlob(dfu_runtime);
  if (write(ep0, descriptors.data(), descriptors.size()) < 0) {
    std::fprintf(stderr, "ffs_selftest: the kernel refused the descriptors%s: %s\n",
                 dfu_runtime ? " (with the DFU functional descriptor)" : "", std::strerror(errno));
    return 3;
  }
  const std::vector<uint8_t> strings = StringBlob(dfu_runtime);
  if (write(ep0, strings.data(), strings.size()) < 0) {
    std::fprintf(stderr, "ffs_selftest: the kernel refused the strings: %s\n", std::strerror(errno));
    return 3;
  }
  std::printf("ffs_selftest: descriptors accepted (%zu bytes%s)\n", descriptors.size(),
              dfu_runtime ? ", with a DFU functional descriptor" : "");

  std::thread(EchoLoop, dir).detach();
  std::array<usb_functionfs_event, 4> events{};
  for (;;) {
    const ssize_t n = read(ep0, events.data(), sizeof(events));
    if (n < 0) {
      if (errno == EINTR) continue;
      std::fprintf(stderr, "ffs_selftest: reading events from ep0 failed: %s\n", std::strerror(errno));
      return 1;
    }
    for (size_t i = 0; i < static_cast<size_t>(n) / sizeof(usb_functionfs_event); ++i) {
      std::printf("ffs_selftest: event %s\n", EventName(events[i].type));
      if (events[i].type == FUNCTIONFS_SETUP) AnswerSetup(ep0, events[i].u.setup, dfu_runtime);
    }
  }
}
