// libFuzzer: MESSAGE_OUT control transfers (SPEC.md §5.3) into a UsbMessageOutReceiver: setup
// stages and data-stage packets in any order (fuzz_input.hpp). A message is exactly the
// wLength bytes of the packets since the last setup.
#include <cstdlib>
#include <cstring>

#include "fuzz_input.hpp"
#include "tetrapulse/protocol/usb_control.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  UsbMessageOutReceiver rx;
  uint8_t sent[kMaxMessageSize + kUsbMaxPacketSize + 1];  // what the packets carried since the setup
  size_t sent_size = 0;
  size_t w_length = 0;  // of the stage in progress, 0 when none
  fuzz::UsbControlRecord r;
  size_t pos = 0;
  while (fuzz::next_usb_control_record(data, size, &pos, &r)) {
    if (r.setup) {
      const Status s = rx.begin(r.w_length);
      if (s.ok() != (r.w_length >= 3 && r.w_length <= kMaxMessageSize)) std::abort();
      w_length = s.ok() ? r.w_length : 0;
      sent_size = 0;
      continue;
    }
    const ReceiveEvent e = rx.push_packet(ByteView{r.packet, r.length});
    if (w_length != 0 && sent_size + r.length <= sizeof(sent)) {
      std::memcpy(sent + sent_size, r.packet, r.length);
      sent_size += r.length;
    }
    if (e.kind == ReceiveKind::kNothing) {
      if (w_length == 0 || r.length != kUsbMaxPacketSize || sent_size >= w_length) std::abort();
      continue;
    }
    if (e.kind == ReceiveKind::kError && e.error == Error::kNone) std::abort();
    if (e.kind == ReceiveKind::kMessage &&
        (e.message.size != w_length || sent_size != w_length || std::memcmp(e.message.data, sent, w_length) != 0)) {
      std::abort();
    }
    w_length = 0;  // a stage ends with a message or an error
    sent_size = 0;
  }
  return 0;
}
