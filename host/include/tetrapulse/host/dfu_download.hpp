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
  virtual ~DfuControl() = default;
  virtual const std::string& name() const = 0;  // names the device in errors
  virtual HostResult<void> download(uint16_t block, protocol::ByteView data) = 0;  // DFU_DNLOAD
  virtual HostResult<protocol::DfuStatus> get_status() = 0;                         // DFU_GETSTATUS
  virtual HostResult<void> clear_status() = 0;                                      // DFU_CLRSTATUS
  virtual HostResult<void> abort() = 0;                                             // DFU_ABORT
  // Waits `ms` (bwPollTimeout); a model in tests advances its own clock instead.
  virtual void wait_ms(uint32_t ms) = 0;
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
