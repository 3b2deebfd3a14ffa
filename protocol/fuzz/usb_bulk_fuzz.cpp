// libFuzzer: the whole input as one bulk transfer, and as a packet stream
// (fuzz_input.hpp) into a UsbBulkFrameReceiver. Every message must re-encode to its transfer.
#include <cstdlib>

#include "fuzz_input.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"

using namespace tetrapulse::protocol;

namespace {

void check(ByteView m) {
  if (m.size < 3 || m.size > kMaxMessageSize) std::abort();
  uint8_t transfer[kUsbBulkMaxTransfer];
  const Result<size_t> n = encode_usb_bulk_frame(m, transfer, sizeof(transfer));
  if (!n || *n != m.size + kUsbBulkHeaderSize) std::abort();
  const Result<ByteView> back = decode_usb_bulk_frame(ByteView{transfer, *n});
  if (!back || back->size != m.size) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Result<ByteView> whole = decode_usb_bulk_frame(ByteView{data, size});
  if (whole) check(*whole);

  UsbBulkFrameReceiver rx;
  size_t pos = 0;
  const uint8_t* packet = nullptr;
  size_t length = 0;
  while (fuzz::next_usb_packet(data, size, &pos, &packet, &length)) {
    const ReceiveEvent e = rx.push_packet(ByteView{packet, length});
    if (e.kind == ReceiveKind::kError && e.error == Error::kNone) std::abort();
    if (e.kind == ReceiveKind::kMessage) check(e.message);
  }
  return 0;
}
