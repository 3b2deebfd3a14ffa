#pragma once
// Walks the fields a struct lists in its static fields(io, m), in wire order. The reader,
// writer, size counter and formatter here are the only code that knows how a field becomes
// bytes, so the encoder and the decoder cannot disagree (SPEC.md §2.1):
//   integers and enums   little-endian, their own size (enums: their underlying type)
//   std::array<uint8_t>  its bytes as they are
//   structs, arrays      their fields in order, no padding
//   tail(count, items)   the count, then `count` items filling the rest of the message
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol::detail {

template <class T>
struct ArrayTraits {
  static constexpr bool kIsArray = false;
};
template <class T, size_t N>
struct ArrayTraits<std::array<T, N>> {
  static constexpr bool kIsArray = true;
  using Item = T;
  static constexpr size_t kCapacity = N;
};

// The integer a scalar field travels as.
template <class T, bool = std::is_enum_v<T>>
struct WireInt {
  using type = T;
};
template <class T>
struct WireInt<T, true> {
  using type = std::underlying_type_t<T>;
};

// Encoded size of a field type (defined below FieldSizer).
template <class T>
size_t encoded_size();

template <class Derived>
class FieldWalker {
 public:
  template <class T>
  void field(const char* name, T& value) {
    using U = std::remove_const_t<T>;
    if constexpr (std::is_integral_v<U> || std::is_enum_v<U>) {
      self().scalar(name, value);
    } else if constexpr (ArrayTraits<U>::kIsArray) {
      items(name, value, ArrayTraits<U>::kCapacity);
    } else {
      self().open(name, -1);
      U::fields(self(), value);
      self().close();
    }
  }

  // A count, then `count` items (at most the array's capacity) that fill the rest of
  // the message: a count the bytes after it disagree with is kBadLength.
  template <class Count, class Array>
  void tail(const char* count_name, Count& count, const char* items_name, Array& array) {
    using Traits = ArrayTraits<std::remove_const_t<Array>>;
    self().scalar(count_name, count);
    if (!ok()) return;
    if (count > Traits::kCapacity) return fail(Error::kBadLength);
    self().expect_remaining(static_cast<size_t>(count) * encoded_size<typename Traits::Item>());
    items(items_name, array, count);
  }

  bool ok() const { return error_ == Error::kNone; }
  Error error() const { return error_; }
  void fail(Error e) {
    if (error_ == Error::kNone) error_ = e;
  }

  // Hooks a walker may hide: a named group begins/ends; the rest of the input must be `n` bytes.
  void open(const char*, long) {}
  void close() {}
  void expect_remaining(size_t) {}

 private:
  template <class Array>
  void items(const char* name, Array& array, size_t n) {
    using Item = typename ArrayTraits<std::remove_const_t<Array>>::Item;
    if (!ok()) return;
    if constexpr (std::is_same_v<Item, uint8_t>) {
      self().bytes(name, array.data(), n);
    } else {
      for (size_t i = 0; i < n && ok(); ++i) {
        self().open(name, static_cast<long>(i));
        Item::fields(self(), array[i]);
        self().close();
      }
    }
  }
  Derived& self() { return static_cast<Derived&>(*this); }

  Error error_ = Error::kNone;
};

// Reads fields from a ByteReader; truncation and length errors stop the walk.
class FieldReader : public FieldWalker<FieldReader> {
 public:
  explicit FieldReader(ByteReader& in) : in_(in) {}

  template <class T>
  void scalar(const char*, T& value) {
    using W = typename WireInt<T>::type;
    uint64_t raw = 0;
    if constexpr (sizeof(W) == 1) raw = in_.u8();
    if constexpr (sizeof(W) == 2) raw = in_.u16();
    if constexpr (sizeof(W) == 4) raw = in_.u32();
    if constexpr (sizeof(W) == 8) raw = in_.u64();
    static_assert(sizeof(W) == 1 || sizeof(W) == 2 || sizeof(W) == 4 || sizeof(W) == 8);
    value = static_cast<T>(static_cast<W>(raw));
    take_reader_error();
  }
  void bytes(const char*, uint8_t* out, size_t n) {
    in_.bytes(out, n);
    take_reader_error();
  }
  void expect_remaining(size_t n) {
    if (in_.remaining() != n) fail(Error::kBadLength);
  }

 private:
  void take_reader_error() {
    if (!in_.ok()) fail(in_.error());
  }
  ByteReader& in_;
};

// Appends fields to a ByteWriter; kBufferTooSmall when they do not fit.
class FieldWriter : public FieldWalker<FieldWriter> {
 public:
  explicit FieldWriter(ByteWriter& out) : out_(out) {}

  template <class T>
  void scalar(const char*, const T& value) {
    using W = typename WireInt<T>::type;
    const auto raw = static_cast<uint64_t>(static_cast<W>(value));
    if constexpr (sizeof(W) == 1) out_.u8(static_cast<uint8_t>(raw));
    if constexpr (sizeof(W) == 2) out_.u16(static_cast<uint16_t>(raw));
    if constexpr (sizeof(W) == 4) out_.u32(static_cast<uint32_t>(raw));
    if constexpr (sizeof(W) == 8) out_.u64(raw);
    take_writer_error();
  }
  void bytes(const char*, const uint8_t* in, size_t n) {
    out_.bytes(in, n);
    take_writer_error();
  }

 private:
  void take_writer_error() {
    if (!out_.ok()) fail(Error::kBufferTooSmall);
  }
  ByteWriter& out_;
};

// Counts encoded bytes.
class FieldSizer : public FieldWalker<FieldSizer> {
 public:
  template <class T>
  void scalar(const char*, const T&) {
    size_ += sizeof(typename WireInt<T>::type);
  }
  void bytes(const char*, const uint8_t*, size_t n) { size_ += n; }
  size_t size() const { return size_; }

 private:
  size_t size_ = 0;
};

template <class T>
size_t encoded_size() {
  const T value{};
  FieldSizer sizer;
  sizer.field("", value);
  return sizer.size();
}

// Writes "name=value" pairs separated by spaces into a bounded text buffer; groups
// read "name={...}", array items "name[i]={...}", byte strings in hex.
class FieldPrinter : public FieldWalker<FieldPrinter> {
 public:
  FieldPrinter(char* out, size_t capacity);

  template <class T>
  void scalar(const char* name, const T& value) {
    using W = typename WireInt<T>::type;
    key(name);
    if constexpr (std::is_signed_v<W>) {
      signed_number(static_cast<int64_t>(static_cast<W>(value)));
    } else {
      unsigned_number(static_cast<uint64_t>(static_cast<W>(value)));
    }
  }
  void bytes(const char* name, const uint8_t* in, size_t n);
  void open(const char* name, long index);
  void close();

  void text(const char* s);
  void unsigned_number(uint64_t v);
  void signed_number(int64_t v);
  // Length of the whole text, even the part that did not fit.
  size_t length() const { return length_; }

 private:
  void key(const char* name);
  void put(char c);

  char* out_;
  size_t capacity_;
  size_t length_ = 0;
  bool separate_ = false;
};

}  // namespace tetrapulse::protocol::detail

namespace tetrapulse::protocol::detail {

// The decoding order of SPEC.md §2.1: read every field of `value` (kTruncated, kBadLength),
// then `validate(value)` (kBadValue, kBadLength), then nothing may be left (kTrailingBytes).
template <class T, class Validate>
Status read_exactly(ByteReader& in, T& value, Validate validate) {
  FieldReader reader(in);
  reader.field("", value);
  if (!reader.ok()) return reader.error();
  if (const Status s = validate(value); !s.ok()) return s;
  if (in.remaining() != 0) return Error::kTrailingBytes;
  return {};
}

// Appends the fields of `value` (kBufferTooSmall if they do not fit).
template <class T>
Status write_fields(ByteWriter& out, const T& value) {
  FieldWriter writer(out);
  writer.field("", value);
  return writer.error();
}

}  // namespace tetrapulse::protocol::detail
