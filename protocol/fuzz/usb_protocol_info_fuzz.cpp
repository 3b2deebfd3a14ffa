// libFuzzer: PROTOCOL_INFO answers (SPEC.md §5.3). An answer decodes exactly when it has at
// least 8 bytes (a later version may append fields), and encodes back to its first 8 bytes,
// the reserved byte aside.
#include <cstdlib>

#include "tetrapulse/protocol/usb_device.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Result<UsbProtocolInfo> info = decode_usb_protocol_info(ByteView{data, size});
  if (info.ok() != (size >= kUsbProtocolInfoSize)) std::abort();
  if (!info) {
    if (info.error() != Error::kTruncated) std::abort();
    return 0;
  }
  uint8_t out[kUsbProtocolInfoSize];
  const Result<size_t> n = encode_usb_protocol_info(*info, out, sizeof(out));
  if (!n || *n != kUsbProtocolInfoSize) std::abort();
  for (size_t i = 0; i < *n; ++i) {
    if (i != 1 && out[i] != data[i]) std::abort();  // byte 1 is reserved
  }
  return 0;
}
