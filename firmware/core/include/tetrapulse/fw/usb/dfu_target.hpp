#pragma once
// Hardware seams behind the DFU state machine (dfu_device.hpp): what a board does when the
// host detaches its application, and where a DFU-mode download goes.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

// Run-time DFU (the application's interface).
class DfuRuntimeTarget {
 public:
  // Leave the application for the DFU-mode bootloader: detach from USB and restart with
  // the bootloader asked to stay (stm32f405: soft disconnect, then a reset through the
  // boot handoff). Called from DfuDevice::poll(), after the host has DETACH's status.
  void detach() { do_detach(); }

 protected:
  ~DfuRuntimeTarget() = default;

 private:
  virtual void do_detach() = 0;
};

// DFU mode: the file a host downloads (stm32f405: ImageBundleWriter into the inactive slot;
// a Linux board: a file). Calls come from DfuDevice::poll(), one at a time, and may take
// as long as the poll timeout they announced (an erase, a flash write); a status other
// than kOk ends the download with that status (dfuERROR) and abort() follows.
class DfuDownloadTarget {
 public:
  // Bytes [offset, offset + block.size) of the file, in order; offset 0 starts a download.
  protocol::DfuStatusCode download(uint32_t offset, protocol::ByteView block) { return do_download(offset, block); }
  // The longest download() of this block may take, in ms (the host waits that long).
  uint32_t download_poll_ms(uint32_t offset, size_t size) const { return do_download_poll_ms(offset, size); }
  // All `size` bytes arrived (the zero-length DFU_DNLOAD): verify and install the file.
  protocol::DfuStatusCode manifest(uint32_t size) { return do_manifest(size); }
  uint32_t manifest_poll_ms() const { return do_manifest_poll_ms(); }
  // The download ended without manifestation (DFU_ABORT, an error, a USB reset).
  void abort() { do_abort(); }
  // DFU_UPLOAD: up to `capacity` bytes from `offset` into `out`, fewer at the end of what
  // there is to read. kNotSupported when the target cannot be read back.
  protocol::Result<size_t> upload(uint32_t offset, uint8_t* out, size_t capacity) {
    return do_upload(offset, out, capacity);
  }

 protected:
  ~DfuDownloadTarget() = default;

 private:
  virtual protocol::DfuStatusCode do_download(uint32_t offset, protocol::ByteView block) = 0;
  virtual uint32_t do_download_poll_ms(uint32_t offset, size_t size) const = 0;
  virtual protocol::DfuStatusCode do_manifest(uint32_t size) = 0;
  virtual uint32_t do_manifest_poll_ms() const = 0;
  virtual void do_abort() = 0;
  virtual protocol::Result<size_t> do_upload(uint32_t, uint8_t*, size_t) { return protocol::Error::kNotSupported; }
};

}  // namespace tetrapulse::fw
