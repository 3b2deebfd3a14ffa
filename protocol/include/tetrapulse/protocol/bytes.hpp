#pragma once
// Bounds-checked little-endian byte reading and writing over caller-owned buffers.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// A read-only view of bytes (C++17 has no std::span).
struct ByteView {
  const uint8_t* data = nullptr;
  size_t size = 0;
  const uint8_t& operator[](size_t i) const { return data[i]; }
  const uint8_t* begin() const { return data; }
  const uint8_t* end() const { return data + size; }
  ByteView subview(size_t offset, size_t count) const {
    if (offset > size) offset = size;
    if (count > size - offset) count = size - offset;
    return ByteView{data + offset, count};
  }
};

// Reads little-endian fields; once a read fails every later read fails too,
// so a decoder can read all fields and check `ok()` once.
class ByteReader {
 public:
  explicit ByteReader(ByteView in) : in_(in) {}
  ByteReader(const uint8_t* data, size_t size) : in_{data, size} {}

  uint8_t u8() { return static_cast<uint8_t>(take(1)); }
  uint16_t u16() { return static_cast<uint16_t>(take(2)); }
  uint32_t u32() { return static_cast<uint32_t>(take(4)); }
  uint64_t u64() { return take(8); }
  int8_t i8() { return static_cast<int8_t>(u8()); }
  int16_t i16() { return static_cast<int16_t>(u16()); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  int64_t i64() { return static_cast<int64_t>(u64()); }
  // Copies `n` bytes into `out`; on failure `out` is left untouched.
  bool bytes(uint8_t* out, size_t n) {
    if (!check(n)) return false;
    for (size_t i = 0; i < n; ++i) out[i] = in_.data[pos_ + i];
    pos_ += n;
    return true;
  }
  // Marks the input as malformed with a specific error (first error wins).
  void fail(Error e) {
    if (error_ == Error::kNone) error_ = e;
  }

  bool ok() const { return error_ == Error::kNone; }
  Error error() const { return error_; }
  size_t position() const { return pos_; }
  size_t remaining() const { return error_ == Error::kNone ? in_.size - pos_ : 0; }

 private:
  bool check(size_t n) {
    if (error_ != Error::kNone) return false;
    if (n > in_.size - pos_) {
      error_ = Error::kTruncated;
      return false;
    }
    return true;
  }
  uint64_t take(size_t n) {
    if (!check(n)) return 0;
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v |= static_cast<uint64_t>(in_.data[pos_ + i]) << (8 * i);
    pos_ += n;
    return v;
  }
  ByteView in_;
  size_t pos_ = 0;
  Error error_ = Error::kNone;
};

// Writes little-endian fields into a fixed buffer; overflow sets kBufferTooSmall.
class ByteWriter {
 public:
  ByteWriter(uint8_t* data, size_t capacity) : data_(data), capacity_(capacity) {}

  void u8(uint8_t v) { put(v, 1); }
  void u16(uint16_t v) { put(v, 2); }
  void u32(uint32_t v) { put(v, 4); }
  void u64(uint64_t v) { put(v, 8); }
  void i8(int8_t v) { put(static_cast<uint8_t>(v), 1); }
  void i16(int16_t v) { put(static_cast<uint16_t>(v), 2); }
  void i32(int32_t v) { put(static_cast<uint32_t>(v), 4); }
  void i64(int64_t v) { put(static_cast<uint64_t>(v), 8); }
  void bytes(const uint8_t* in, size_t n) {
    if (!check(n)) return;
    for (size_t i = 0; i < n; ++i) data_[size_ + i] = in[i];
    size_ += n;
  }

  bool ok() const { return ok_; }
  size_t size() const { return size_; }
  const uint8_t* data() const { return data_; }
  ByteView view() const { return ByteView{data_, size_}; }

 private:
  bool check(size_t n) {
    if (!ok_) return false;
    if (n > capacity_ - size_) {
      ok_ = false;
      return false;
    }
    return true;
  }
  void put(uint64_t v, size_t n) {
    if (!check(n)) return;
    for (size_t i = 0; i < n; ++i) data_[size_ + i] = static_cast<uint8_t>(v >> (8 * i));
    size_ += n;
  }
  uint8_t* data_;
  size_t capacity_;
  size_t size_ = 0;
  bool ok_ = true;
};

}  // namespace tetrapulse::protocol
