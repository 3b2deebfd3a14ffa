#pragma once
// Consistent Overhead Byte Stuffing (Cheshire & Baker, IEEE/ACM ToN 1999): rewrites
// data so that it contains no 0x00, which then delimits frames.
//
// Each block is a code byte c (1..255) followed by c-1 non-zero data bytes; a block
// with c < 255 stands for its data followed by 0x00, except the last block, whose
// zero is dropped. The encoder never ends with an empty block after a 255-block
// (so n bytes encode to exactly cobs_max_encoded_size(n) bytes when none is 0x00);
// decoders also accept that trailing 0x01, as it decodes to the same data.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// Largest encoding of `size` bytes (without the delimiter): size + ceil(size/254), at least 1.
constexpr size_t cobs_max_encoded_size(size_t size) {
  return size == 0 ? 1 : size + (size + 253) / 254;
}

// Encodes byte by byte into a caller buffer, so that a frame can be stuffed while
// its parts (message, CRC) are produced.
class CobsEncoder {
 public:
  CobsEncoder(uint8_t* out, size_t capacity) : out_(out), capacity_(capacity) {}
  void put(uint8_t byte);
  void put(ByteView bytes);
  // Closes the last block; the encoded size, or kBufferTooSmall if anything did not fit.
  Result<size_t> finish();

 private:
  void emit(uint8_t byte);
  void close_block(bool ended_by_zero);
  uint8_t* out_;
  size_t capacity_;
  size_t size_ = 0;
  size_t code_at_ = 0;       // where the open block's code byte goes
  uint8_t code_ = 1;         // code of the open block so far
  bool open_ = false;        // a block is open
  bool owes_block_ = true;   // data so far ends in 0x00 (or is empty): a final block must follow
  bool ok_ = true;
};

Result<size_t> cobs_encode(ByteView in, uint8_t* out, size_t capacity);

// Decodes byte by byte; the caller splits frames at delimiters and calls reset()
// at each one.
class CobsDecoder {
 public:
  void reset() { *this = CobsDecoder{}; }
  // Feeds one encoded byte (never 0x00). A code byte yields the 0x00 the previous
  // block ends with, if any; a data byte yields itself. Returns whether `*out` was set.
  bool feed(uint8_t byte, uint8_t* out);
  // True when the bytes fed since reset() form a complete encoding.
  bool complete() const { return started_ && remaining_ == 0; }

 private:
  uint8_t remaining_ = 0;   // data bytes still due in the open block
  bool zero_owed_ = false;  // the open block ends with an implied 0x00
  bool started_ = false;
};

// Decodes a whole encoding (no delimiter). kBadFraming for a 0x00 in the input, an
// empty input or a block cut short; kBufferTooSmall when the output does not fit.
Result<size_t> cobs_decode(ByteView in, uint8_t* out, size_t capacity);

}  // namespace tetrapulse::protocol
