#pragma once
// The USB DFU 1.1 device state machine (USB-IF "Device Class Specification for Device
// Firmware Upgrade" 1.1, §6 and appendix A; SPEC.md §5.6), independent of the USB
// controller: the STM32 firmware runs it behind UsbControl, a Linux board behind a
// FunctionFS gadget.
//
// Run-time mode (application, appIDLE/appDETACH): GETSTATUS, GETSTATE, DETACH. With
// bitWillDetach the device detaches itself once DETACH's status stage is done; without
// it, at the next USB reset within wDetachTimeOut (after that: appIDLE again).
//
// DFU mode (bootloader), as dfu-util 0.11 drives it:
//   DNLOAD(block n, wLength <= wTransferSize)  dfuIDLE / dfuDNLOAD-IDLE -> dfuDNLOAD-SYNC
//   GETSTATUS                                  -> dfuDNBUSY, bwPollTimeout = the target's
//                                                 estimate; the block is written in poll()
//   GETSTATUS (after the poll timeout)         -> dfuDNLOAD-IDLE
//   ... until DNLOAD with wLength 0            dfuDNLOAD-IDLE -> dfuMANIFEST-SYNC
//   GETSTATUS                                  -> dfuMANIFEST; poll() verifies and installs
//   GETSTATUS                                  -> dfuIDLE + OK (bitManifestationTolerant),
//                                                 or dfuERROR + the target's status
//   without bitManifestationTolerant: dfuMANIFEST-WAIT-RESET until the USB reset (GETSTATUS
//   still answers, so dfu-util sees the state and resets the bus; all else stalls).
// UPLOAD (bitCanUpload) reads the target from offset 0 in wLength blocks until a short one.
// ABORT (dfuIDLE, dfuDNLOAD-IDLE, dfuUPLOAD-IDLE) ends a transfer; CLRSTATUS leaves
// dfuERROR. Any other request, a request in dfuDNBUSY or dfuMANIFEST (the host must wait
// bwPollTimeout), or a DNLOAD longer than wTransferSize stalls and enters dfuERROR with
// errSTALLEDPKT (ending a download in progress). A USB reset ends a download in progress.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/usb/dfu_target.hpp"
#include "tetrapulse/fw/usb/usb_function.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::fw {

class DfuDevice final : public UsbFunction {
 public:
  // Run-time (the application's DFU interface). `params`: the functional descriptor's
  // attributes and wDetachTimeOut.
  DfuDevice(DfuRuntimeTarget& target, const protocol::UsbDeviceParams& params);
  // DFU mode (the bootloader's). `block` holds one DNLOAD data stage: at least
  // params.dfu_transfer_size bytes, else DNLOADs longer than `capacity` stall.
  DfuDevice(DfuDownloadTarget& target, const protocol::UsbDeviceParams& params, uint8_t* block, size_t capacity);

  // Main loop: writes the block or manifests the download the host was told to wait for,
  // detaches, and runs the run-time detach timeout. `now_ms`: any millisecond counter.
  void poll(uint32_t now_ms);

  protocol::DfuState state() const { return state_; }
  protocol::DfuStatusCode status() const { return status_; }
  // DFU mode: a download was installed and the host has its verdict (GETSTATUS answered
  // dfuIDLE after the manifestation, or the USB reset in dfuMANIFEST-WAIT-RESET). The
  // board may restart into the new firmware.
  bool installed() const { return installed_; }

 private:
  enum class Work : uint8_t { kNone, kWrite, kManifest, kDetach };

  UsbControlReply do_setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) override;
  bool do_data_out(const UsbSetup& setup, protocol::ByteView data) override;
  void do_status_complete(const UsbSetup& setup) override;
  void do_bus_reset() override;

  UsbControlReply runtime_request(const UsbSetup& setup, uint8_t* scratch, size_t capacity);
  UsbControlReply state_request(const UsbSetup& setup, uint8_t* scratch, size_t capacity);
  UsbControlReply get_status(uint8_t* scratch, size_t capacity);
  UsbControlReply download(const UsbSetup& setup);
  UsbControlReply upload(const UsbSetup& setup, uint8_t* scratch, size_t capacity);
  // Stalls the request; in DFU mode also enters dfuERROR (errSTALLEDPKT).
  UsbControlReply refuse();
  void fail(protocol::DfuStatusCode status);
  // Back to dfuIDLE, ending a download in progress at the target.
  void end_transfer();
  bool downloading() const;

  DfuRuntimeTarget* runtime_ = nullptr;
  DfuDownloadTarget* target_ = nullptr;
  uint8_t attributes_;
  uint16_t detach_timeout_ms_;
  uint16_t transfer_size_;
  uint8_t* block_ = nullptr;
  size_t capacity_ = 0;

  protocol::DfuState state_;
  protocol::DfuStatusCode status_ = protocol::DfuStatusCode::kOk;
  Work scheduled_ = Work::kNone;  // announced by GETSTATUS, starts after its status stage
  Work ready_ = Work::kNone;      // for poll()
  uint32_t offset_ = 0;           // download: bytes written; upload: bytes read
  size_t block_size_ = 0;         // the block waiting in `block_`
  bool block_written_ = false;
  bool manifested_ = false;
  bool verdict_pending_ = false;  // GETSTATUS is telling the host the manifestation succeeded
  bool installed_ = false;
  bool detach_armed_ = false;     // run-time without bitWillDetach: waiting for the USB reset
  bool detach_clock_started_ = false;
  uint32_t detach_since_ms_ = 0;
};

}  // namespace tetrapulse::fw
