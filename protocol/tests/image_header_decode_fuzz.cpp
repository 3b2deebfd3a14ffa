// libFuzzer: decode_image_header() on any bytes never crashes or reads outside the input;
// a header that decodes re-encodes to the first 64 input bytes and decodes again.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "tetrapulse/protocol/image_header.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto decoded = decode_image_header(ByteView{data, size});
  if (!decoded.ok()) {
    if (decoded.error() == Error::kNone) std::abort();
    return 0;
  }
  if (!validate(*decoded).ok()) std::abort();
  uint8_t buffer[kImageHeaderSize];
  ByteWriter out(buffer, sizeof(buffer));
  if (!encode_image_header(*decoded, out).ok()) std::abort();
  if (std::memcmp(buffer, data, kImageHeaderSize) != 0) std::abort();
  if (!decode_image_header(out.view()).ok()) std::abort();
  // The board-side checks run on whatever the rest of the input is.
  (void)fits(*decoded, HwModel::kStm32f405Reference, 1);
  (void)check_payload(*decoded, ByteView{data, size});
  return 0;
}
