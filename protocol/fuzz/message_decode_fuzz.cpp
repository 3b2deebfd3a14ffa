// libFuzzer: decode() on any bytes never crashes or reads outside the input, and a failure
// stops inside the input (ErrorResponse.detail); whatever decodes is valid, re-encodes to
// exactly the input (the encoding is canonical) and formats within bounds.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "tetrapulse/protocol/message.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  size_t stopped_at = size + 1;
  const auto decoded = decode(ByteView{data, size}, &stopped_at);
  if (!decoded.ok()) {
    if (decoded.error() == Error::kNone || stopped_at > size) std::abort();
    return 0;
  }
  if (!validate(*decoded).ok()) std::abort();
  uint8_t buffer[kMaxMessageSize];
  ByteWriter out(buffer, sizeof(buffer));
  if (!encode(*decoded, out).ok()) std::abort();
  if (out.size() != size || std::memcmp(buffer, data, size) != 0) std::abort();
  const auto again = decode(out.view());
  if (!again.ok() || again->type() != decoded->type()) std::abort();

  char text[64];  // deliberately short: the formatter must truncate, not overflow
  const size_t needed = format_message(*decoded, text, sizeof(text));
  if (std::strlen(text) != (needed < sizeof(text) ? needed : sizeof(text) - 1)) std::abort();
  return 0;
}
