// libFuzzer: a byte stream into a UartFrameDecoder, in pieces whose sizes come from
// the first byte. Every delivered message must re-encode into a frame that decodes to it.
#include <cstdlib>

#include "tetrapulse/protocol/uart_frame.hpp"

using namespace tetrapulse::protocol;

namespace {

void check(ByteView m) {
  if (m.size < 3 || m.size > kMaxMessageSize) std::abort();
  uint8_t frame[kUartMaxFrameSize];
  const Result<size_t> n = encode_uart_frame(m, frame, sizeof(frame));
  if (!n) std::abort();
  UartFrameDecoder again;
  size_t used = 0;
  const ReceiveEvent e = again.feed(ByteView{frame, *n}, &used);
  if (e.kind != ReceiveKind::kMessage || used != *n || e.message.size != m.size) std::abort();
  for (size_t i = 0; i < m.size; ++i) {
    if (e.message[i] != m[i]) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const size_t piece = 1 + data[0] % 64;
  UartFrameDecoder decoder;
  size_t pos = 1;
  while (pos < size) {
    const size_t n = size - pos < piece ? size - pos : piece;
    size_t done = 0;
    while (done < n) {
      size_t used = 0;
      const ReceiveEvent e = decoder.feed(ByteView{data + pos + done, n - done}, &used);
      if (used == 0) std::abort();
      done += used;
      if (e.kind == ReceiveKind::kError && e.error == Error::kNone) std::abort();
      if (e.kind == ReceiveKind::kMessage) check(e.message);
    }
    pos += n;
  }
  return 0;
}
