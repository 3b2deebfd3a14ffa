// libFuzzer: cobs_decode() of one encoding (no delimiter) never crashes or reads outside the
// input, and the encoding is canonical: whatever decodes re-encodes to exactly the input,
// or to the input without the empty last block a decoder also accepts after a 255-block.
#include <cstdlib>
#include <cstring>

#include "tetrapulse/protocol/cobs.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  uint8_t decoded[kUartMaxFrameSize];
  const Result<size_t> n = cobs_decode(ByteView{data, size}, decoded, sizeof(decoded));
  if (!n) {
    if (n.error() == Error::kNone) std::abort();
    return 0;
  }
  if (*n >= size) std::abort();  // every block costs a code byte

  uint8_t encoded[cobs_max_encoded_size(kUartMaxFrameSize)];
  const Result<size_t> e = cobs_encode(ByteView{decoded, *n}, encoded, sizeof(encoded));
  if (!e || *e > cobs_max_encoded_size(*n)) std::abort();
  const bool same = *e == size && std::memcmp(encoded, data, size) == 0;
  const bool same_but_empty_block = *e + 1 == size && std::memcmp(encoded, data, *e) == 0 && data[*e] == 0x01;
  if (!same && !same_but_empty_block) std::abort();
  return 0;
}
