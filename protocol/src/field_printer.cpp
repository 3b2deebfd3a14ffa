#include "field_io.hpp"

namespace tetrapulse::protocol::detail {

FieldPrinter::FieldPrinter(char* out, size_t capacity) : out_(out), capacity_(capacity) {
  if (capacity_ > 0) out_[0] = '\0';
}

void FieldPrinter::put(char c) {
  // Keep one byte for the terminating NUL.
  if (length_ + 1 < capacity_) {
    out_[length_] = c;
    out_[length_ + 1] = '\0';
  }
  ++length_;
}

void FieldPrinter::text(const char* s) {
  while (*s != '\0') put(*s++);
}

void FieldPrinter::unsigned_number(uint64_t v) {
  char digits[20];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  while (n > 0) put(digits[--n]);
}

void FieldPrinter::signed_number(int64_t v) {
  if (v < 0) {
    put('-');
    // Negate in unsigned arithmetic so INT64_MIN does not overflow.
    unsigned_number(0 - static_cast<uint64_t>(v));
  } else {
    unsigned_number(static_cast<uint64_t>(v));
  }
}

void FieldPrinter::key(const char* name) {
  if (separate_) put(' ');
  text(name);
  put('=');
  separate_ = true;
}

void FieldPrinter::bytes(const char* name, const uint8_t* in, size_t n) {
  static constexpr char kHex[] = "0123456789abcdef";
  key(name);
  for (size_t i = 0; i < n; ++i) {
    put(kHex[in[i] >> 4]);
    put(kHex[in[i] & 0xF]);
  }
}

void FieldPrinter::open(const char* name, long index) {
  if (separate_) put(' ');
  text(name);
  if (index >= 0) {
    put('[');
    unsigned_number(static_cast<uint64_t>(index));
    put(']');
  }
  text("={");
  separate_ = false;
}

void FieldPrinter::close() {
  put('}');
  separate_ = true;
}

}  // namespace tetrapulse::protocol::detail
