// libFuzzer: decode_image_header() on any bytes never crashes or reads outside the input;
// a header that decodes re-encodes to the first 64 input bytes and decodes again.
// Each input is tried twice: as it is, and with header_crc32c recomputed, so that
// mutations also reach the field checks behind the CRC.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"

using namespace tetrapulse::protocol;

namespace {

void check(const uint8_t* data, size_t size) {
  const auto decoded = decode_image_header(ByteView{data, size});
  if (!decoded.ok()) {
    if (decoded.error() == Error::kNone) std::abort();
    return;
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
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  check(data, size);
  if (size < kImageHeaderSize) return 0;
  // A copy of exactly `size` bytes (ASan still sees reads past the end) with a valid CRC.
  uint8_t* fixed = static_cast<uint8_t*>(std::malloc(size));
  if (fixed == nullptr) return 0;
  std::memcpy(fixed, data, size);
  const uint32_t crc = crc32c(fixed, 60);
  for (size_t i = 0; i < 4; ++i) fixed[60 + i] = static_cast<uint8_t>(crc >> (8 * i));
  check(fixed, size);
  std::free(fixed);
  return 0;
}
