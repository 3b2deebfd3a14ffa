// libFuzzer: DFU_GETSTATUS answers (SPEC.md §5.6). Whatever decodes must encode back to the
// same bytes.
#include <cstdlib>

#include "tetrapulse/protocol/dfu.hpp"

using namespace tetrapulse::protocol;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Result<DfuStatus> status = decode_dfu_status(ByteView{data, size});
  if (!status) {
    if (status.error() == Error::kNone) std::abort();
    return 0;
  }
  uint8_t out[kDfuStatusSize];
  const Result<size_t> n = encode_dfu_status(*status, out, sizeof(out));
  if (!n || *n != size) std::abort();
  for (size_t i = 0; i < size; ++i) {
    if (out[i] != data[i]) std::abort();
  }
  return 0;
}
