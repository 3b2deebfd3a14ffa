#pragma once
// A USB DFU 1.1 download, the host side (USB-IF DFU 1.1 §6.1, as dfu-util speaks it), over
// any DFU-mode device: the image goes in DFU_DNLOAD blocks of wTransferSize bytes numbered
// from 0; after each, DFU_GETSTATUS is repeated, waiting bwPollTimeout each time, until the
// device is in dfuDNLOAD-IDLE; a zero-length DFU_DNLOAD ends the download and starts
// manifestation, polled the same way until dfuIDLE (manifestation tolerant) or
// dfuMANIFEST-WAIT-RESET. A device found in dfuERROR is cleared (DFU_CLRSTATUS) first and
// one found mid-transfer is aborted (DFU_ABORT).
#include <cstddef>
#include <cstdint>
#include <string>

#include "tetrapulse/host/flash_progress.hpp"
#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/dfu.hpp"

namespace tetrapulse::host {

// The DFU class requests to one DFU-mode interface.
class DfuControl {
 public:
  const std::string& name() const { return do_name(); }  // names the device in errors
  HostResult<void> download(uint16_t block, protocol::ByteView data) { return do_download(block, data); }  // DFU_DNLOAD
  HostResult<protocol::DfuStatus> get_status() { return do_get_status(); }  // DFU_GETSTATUS
  HostResult<void> clear_status() { return do_clear_status(); }             // DFU_CLRSTATUS
  HostResult<void> abort() { return do_abort(); }                           // DFU_ABORT
  // Waits `ms` (bwPollTimeout); a model in tests advances its own clock instead.
  void wait_ms(uint32_t ms) { do_wait_ms(ms); }

 protected:
  ~DfuControl() = default;  // used by reference, never owned through the base

 private:
  virtual const std::string& do_name() const = 0;
  virtual HostResult<void> do_download(uint16_t block, protocol::ByteView data) = 0;
  virtual HostResult<protocol::DfuStatus> do_get_status() = 0;
  virtual HostResult<void> do_clear_status() = 0;
  virtual HostResult<void> do_abort() = 0;
  virtual void do_wait_ms(uint32_t ms) = 0;
};

struct DfuDownloadOptions {
  size_t transfer_size = 1024;  // wTransferSize of the functional descriptor
  // Most GETSTATUS polls after one request before the device counts as hung.
  uint32_t max_polls = 1000;
  FlashProgressCallback progress;  // stages "download" (bytes) and "manifest"
  const CancelFlag* cancel = nullptr;
};

struct DfuDownloadReport {
  uint32_t blocks = 0;
  uint32_t polls = 0;
  bool needs_reset = false;  // the device ended in dfuMANIFEST-WAIT-RESET
};

HostResult<DfuDownloadReport> dfu_download(DfuControl& device, protocol::ByteView image,
                                           const DfuDownloadOptions& options);

const char* dfu_state_name(protocol::DfuState state);
const char* dfu_status_name(protocol::DfuStatusCode status);

}  // namespace tetrapulse::host
