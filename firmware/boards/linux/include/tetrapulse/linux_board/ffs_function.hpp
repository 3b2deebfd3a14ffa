#pragma once
// The USB device side of the Linux board: one FunctionFS function (the kernel's
// usb_f_fs) carrying the board's interfaces. The kernel answers the standard requests
// from the descriptors written here (protocol::build_usb_function_descriptors, the same
// bytes the STM32 board sends); class and vendor requests to an interface arrive as SETUP
// events on ep0 and go to the core's UsbFunction behind that interface
// (UsbMessageFunction, DfuDevice). Bulk OUT transfers are read by a thread and handed to
// the main loop; bulk IN transfers (UsbPipe) are written by another, as FunctionFS
// endpoint files block until the host takes the data.
//
// FunctionFS limits: an OUT request's status stage follows its data stage at once, so a
// data stage the function refuses cannot be stalled (the function's state records the
// refusal, e.g. DFU's dfuERROR); descriptors and strings must be written before the
// gadget is bound to a UDC.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/usb_function.hpp"
#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::linux_board {

// What FunctionFS takes on ep0 before binding: the descriptors (full and high speed; the
// high-speed bulk endpoints with 512-byte packets) and the string table (indices 1..4 of
// protocol/usb_device.hpp).
struct FfsBlobs {
  std::vector<uint8_t> descriptors;
  std::vector<uint8_t> strings;
};
FfsBlobs ffs_blobs(const protocol::UsbDeviceParams& params, const std::string& serial);

struct BulkTransfer {
  std::vector<uint8_t> bytes;
  int64_t monotonic_ns = 0;  // when the read completed
};

class FfsFunction final : public fw::UsbPipe {
 public:
  // Opens `mount_dir`/ep0 of a mounted FunctionFS and writes the blobs; in application
  // mode opens the bulk endpoints and starts their threads. kUsbGadget naming the endpoint
  // file that failed.
  static BoardResult<std::unique_ptr<FfsFunction>> open(const std::string& mount_dir,
                                                        const protocol::UsbDeviceParams& params,
                                                        const std::string& serial);
  ~FfsFunction();
  FfsFunction(const FfsFunction&) = delete;
  FfsFunction& operator=(const FfsFunction&) = delete;

  // The function behind interface `number` (0 or 1).
  void set_function(uint8_t number, fw::UsbFunction& function);

  int ep0_fd() const { return ep0_; }
  // Readable (an eventfd) while bulk OUT transfers wait for take_bulk().
  int bulk_fd() const { return bulk_event_; }
  // Reads the ep0 events waiting and answers their requests. Returns the names of the
  // bus events seen ("BIND", "ENABLE", "DISABLE", "UNBIND", ...), for the log.
  std::vector<const char*> handle_ep0();
  std::vector<BulkTransfer> take_bulk();
  // Waits up to `timeout_ms` until the host has taken every bulk IN transfer queued (a
  // reboot's Ack must leave before the board restarts).
  void drain(int timeout_ms);

  bool enabled() const { return enabled_; }
  // CLOCK_MONOTONIC time of the last class or vendor request (DFU idle timeouts).
  int64_t last_request_ns() const { return last_request_ns_; }

  // The bulk endpoints and their queues, shared with the endpoint threads (which block
  // in FunctionFS reads and writes and end only with the process).
  struct Bulk;

 private:
  FfsFunction() = default;
  protocol::Status do_send_bulk(protocol::ByteView transfer) override;
  void answer(const fw::UsbSetup& setup);
  void reset_functions();

  int ep0_ = -1;
  fw::UsbFunction* functions_[2] = {};
  uint8_t scratch_[4096] = {};
  bool enabled_ = false;
  int64_t last_request_ns_ = 0;
  int bulk_event_ = -1;
  std::shared_ptr<Bulk> bulk_;
};

}  // namespace tetrapulse::linux_board
