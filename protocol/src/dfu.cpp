#include "tetrapulse/protocol/dfu.hpp"

namespace tetrapulse::protocol {

Result<size_t> encode_dfu_status(const DfuStatus& status, uint8_t* out, size_t capacity) {
  if (status.poll_timeout_ms > kDfuMaxPollTimeoutMs ||
      static_cast<uint8_t>(status.status) > kDfuLastStatusCode ||
      static_cast<uint8_t>(status.state) > kDfuLastState) {
    return Error::kBadValue;
  }
  ByteWriter w(out, capacity);
  w.u8(static_cast<uint8_t>(status.status));
  w.u16(static_cast<uint16_t>(status.poll_timeout_ms));
  w.u8(static_cast<uint8_t>(status.poll_timeout_ms >> 16));
  w.u8(static_cast<uint8_t>(status.state));
  w.u8(status.string_index);
  if (!w.ok()) return Error::kBufferTooSmall;
  return w.size();
}

Result<DfuStatus> decode_dfu_status(ByteView in) {
  if (in.size > kDfuStatusSize) return Error::kTrailingBytes;
  ByteReader r(in);
  const uint8_t status = r.u8();
  const uint16_t poll_low = r.u16();
  const uint8_t poll_high = r.u8();
  const uint8_t state = r.u8();
  const uint8_t string_index = r.u8();
  if (!r.ok()) return r.error();
  if (status > kDfuLastStatusCode || state > kDfuLastState) return Error::kBadValue;
  DfuStatus out;
  out.status = static_cast<DfuStatusCode>(status);
  out.poll_timeout_ms = static_cast<uint32_t>(poll_low) | (static_cast<uint32_t>(poll_high) << 16);
  out.state = static_cast<DfuState>(state);
  out.string_index = string_index;
  return out;
}

}  // namespace tetrapulse::protocol
