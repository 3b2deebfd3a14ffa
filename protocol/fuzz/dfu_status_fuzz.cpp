// libFuzzer: DFU_GETSTATUS answers and PROTOCOL_INFO answers. Whatever decodes must
// encode back to the same bytes.
#include <cstdlib>

#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Result<DfuStatus> status = decode_dfu_status(ByteView{data, size});
  if (status) {
    uint8_t out[kDfuStatusSize];
    const Result<size_t> n = encode_dfu_status(*status, out, sizeof(out));
    if (!n || *n != size) std::abort();
    for (size_t i = 0; i < size; ++i) {
      if (out[i] != data[i]) std::abort();
    }
  }
  const Result<UsbProtocolInfo> info = decode_usb_protocol_info(ByteView{data, size});
  if (info) {
    uint8_t out[kUsbProtocolInfoSize];
    const Result<size_t> n = encode_usb_protocol_info(*info, out, sizeof(out));
    if (!n) std::abort();
    for (size_t i = 0; i < *n; ++i) {
      if (i != 1 && out[i] != data[i]) std::abort();  // byte 1 is reserved
    }
  }
  return 0;
}
