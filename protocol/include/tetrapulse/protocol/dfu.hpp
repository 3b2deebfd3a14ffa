#pragma once
// USB Device Firmware Upgrade 1.1 facts (USB-IF "Universal Serial Bus Device Class
// Specification for Device Firmware Upgrade", version 1.1, 2004) and the 6-byte
// DFU_GETSTATUS answer. SPEC.md §5.6.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

constexpr uint8_t kDfuInterfaceClass = 0xFE;       // application specific
constexpr uint8_t kDfuInterfaceSubclass = 0x01;    // device firmware upgrade
constexpr uint8_t kDfuProtocolRuntime = 0x01;      // beside the application's interfaces
constexpr uint8_t kDfuProtocolDfuMode = 0x02;      // the only interface, in the bootloader
constexpr uint8_t kDfuFunctionalDescriptorType = 0x21;
constexpr uint8_t kDfuFunctionalDescriptorSize = 9;
constexpr uint16_t kDfuVersionBcd = 0x0110;

// bmRequestType of DFU class requests to the interface.
constexpr uint8_t kDfuRequestTypeOut = 0x21;  // host to device, class, interface
constexpr uint8_t kDfuRequestTypeIn = 0xA1;   // device to host, class, interface

// bmAttributes of the DFU functional descriptor.
constexpr uint8_t kDfuCanDownload = 1u << 0;
constexpr uint8_t kDfuCanUpload = 1u << 1;
constexpr uint8_t kDfuManifestationTolerant = 1u << 2;
constexpr uint8_t kDfuWillDetach = 1u << 3;
// tetrapulse boards: download only (images are verified by CRC, never read back);
// the application detaches itself on DFU_DETACH (resets into the bootloader); the
// bootloader stays on the bus after manifestation so the host can read the verdict.
constexpr uint8_t kDfuDefaultAttributes = kDfuCanDownload | kDfuManifestationTolerant | kDfuWillDetach;

enum class DfuRequest : uint8_t {
  kDetach = 0,
  kDownload = 1,
  kUpload = 2,
  kGetStatus = 3,
  kClearStatus = 4,
  kGetState = 5,
  kAbort = 6,
};

enum class DfuState : uint8_t {
  kAppIdle = 0,
  kAppDetach = 1,
  kDfuIdle = 2,
  kDfuDownloadSync = 3,
  kDfuDownloadBusy = 4,
  kDfuDownloadIdle = 5,
  kDfuManifestSync = 6,
  kDfuManifest = 7,
  kDfuManifestWaitReset = 8,
  kDfuUploadIdle = 9,
  kDfuError = 10,
};
constexpr uint8_t kDfuLastState = 10;

enum class DfuStatusCode : uint8_t {
  kOk = 0x00,
  kErrTarget = 0x01,        // file not for this device
  kErrFile = 0x02,          // file fails a vendor verification
  kErrWrite = 0x03,
  kErrErase = 0x04,
  kErrCheckErased = 0x05,
  kErrProg = 0x06,
  kErrVerify = 0x07,
  kErrAddress = 0x08,
  kErrNotDone = 0x09,       // end of download before the image was complete
  kErrFirmware = 0x0A,      // firmware corrupt: cannot return to run-time
  kErrVendor = 0x0B,
  kErrUsbReset = 0x0C,
  kErrPowerOnReset = 0x0D,
  kErrUnknown = 0x0E,
  kErrStalledPacket = 0x0F,
};
constexpr uint8_t kDfuLastStatusCode = 0x0F;

// The DFU_GETSTATUS answer:
//   0 bStatus  1..3 bwPollTimeout (ms, 24-bit little-endian)  4 bState  5 iString
struct DfuStatus {
  DfuStatusCode status = DfuStatusCode::kOk;
  uint32_t poll_timeout_ms = 0;  // 0..0xFFFFFF: wait this long before the next GETSTATUS
  DfuState state = DfuState::kDfuIdle;
  uint8_t string_index = 0;      // string descriptor describing the status, 0 = none

  bool operator==(const DfuStatus& o) const {
    return status == o.status && poll_timeout_ms == o.poll_timeout_ms && state == o.state &&
           string_index == o.string_index;
  }
};
constexpr size_t kDfuStatusSize = 6;
constexpr uint32_t kDfuMaxPollTimeoutMs = 0xFFFFFF;

// kBadValue for a poll timeout over 24 bits or an undefined status or state;
// kBufferTooSmall when capacity < 6.
Result<size_t> encode_dfu_status(const DfuStatus& status, uint8_t* out, size_t capacity);
// kTruncated under 6 bytes, kTrailingBytes over 6, kBadValue for an undefined status or state.
Result<DfuStatus> decode_dfu_status(ByteView in);

}  // namespace tetrapulse::protocol
