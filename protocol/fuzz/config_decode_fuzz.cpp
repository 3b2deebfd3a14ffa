// libFuzzer: decode_config() (a flash record, or SetConfig's body) on any bytes never
// crashes or reads outside the input; whatever decodes is valid and re-encodes to exactly
// the input.
#include <cstdlib>
#include <cstring>

#include "tetrapulse/protocol/config.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Result<Config> config = decode_config(ByteView{data, size});
  if (!config) {
    if (config.error() == Error::kNone) std::abort();
    return 0;
  }
  if (!validate(*config).ok()) std::abort();
  uint8_t buffer[kConfigSize];
  ByteWriter out(buffer, sizeof(buffer));
  if (!encode_config(*config, out).ok()) std::abort();
  if (out.size() != size || std::memcmp(buffer, data, size) != 0) std::abort();
  return 0;
}
