#include "tetrapulse/protocol/cobs.hpp"

namespace tetrapulse::protocol {

void CobsEncoder::emit(uint8_t byte) {
  if (!ok_ || size_ >= capacity_) {
    ok_ = false;
    return;
  }
  out_[size_++] = byte;
}

void CobsEncoder::close_block(bool ended_by_zero) {
  if (ok_) out_[code_at_] = code_;
  open_ = false;
  owes_block_ = ended_by_zero;
}

void CobsEncoder::put(uint8_t byte) {
  if (!open_) {
    code_at_ = size_;
    emit(0);  // placeholder for the code byte
    code_ = 1;
    open_ = true;
  }
  if (byte == 0) {
    close_block(true);
    return;
  }
  emit(byte);
  if (++code_ == 0xFF) close_block(false);
}

void CobsEncoder::put(ByteView bytes) {
  for (uint8_t b : bytes) put(b);
}

Result<size_t> CobsEncoder::finish() {
  if (open_) {
    close_block(false);
  } else if (owes_block_) {
    emit(1);
  }
  owes_block_ = false;
  if (!ok_) return Error::kBufferTooSmall;
  return size_;
}

Result<size_t> cobs_encode(ByteView in, uint8_t* out, size_t capacity) {
  CobsEncoder encoder(out, capacity);
  encoder.put(in);
  return encoder.finish();
}

bool CobsDecoder::feed(uint8_t byte, uint8_t* out) {
  if (remaining_ == 0) {
    const bool owed = zero_owed_ && started_;
    started_ = true;
    zero_owed_ = byte != 0xFF;
    remaining_ = static_cast<uint8_t>(byte - 1);
    if (owed) *out = 0;
    return owed;
  }
  --remaining_;
  *out = byte;
  return true;
}

Result<size_t> cobs_decode(ByteView in, uint8_t* out, size_t capacity) {
  CobsDecoder decoder;
  size_t size = 0;
  for (uint8_t b : in) {
    if (b == 0) return Error::kBadFraming;
    uint8_t decoded = 0;
    if (!decoder.feed(b, &decoded)) continue;
    if (size >= capacity) return Error::kBufferTooSmall;
    out[size++] = decoded;
  }
  if (!decoder.complete()) return Error::kBadFraming;
  return size;
}

}  // namespace tetrapulse::protocol
