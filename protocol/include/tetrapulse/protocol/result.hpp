#pragma once
// Freestanding result type: a value or a typed error. No heap, no exceptions.
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>

namespace tetrapulse::protocol {

// Every way a protocol operation can fail. The numeric values are wire values
// (they travel in ErrorResponse, SPEC.md §Errors): never renumber, only append.
enum class Error : uint8_t {
  kNone = 0,
  // Decoding
  kTruncated = 1,         // input ends before the field that was being read
  kBadVersion = 2,        // protocol version byte not understood
  kUnknownMessage = 3,    // message type not defined
  kBadLength = 4,         // a length field disagrees with the data
  kBadValue = 5,          // a field holds a value outside its range
  kBadCrc = 6,            // checksum mismatch
  kTrailingBytes = 7,     // bytes left over after a complete message
  kBadFraming = 8,        // transport framing broken (COBS, CAN toggle/sequence)
  kBufferTooSmall = 9,    // output does not fit the caller's buffer
  // Commands
  kNotSupported = 16,     // valid message this board does not implement
  kBusy = 17,             // try again later
  kInvalidState = 18,     // not allowed now (e.g. update chunk without begin)
  kFlashError = 19,       // flash erase/program/verify failed
  kImageRejected = 20,    // firmware image header, size, version or CRC wrong
  kAccessDenied = 21,     // operation locked (e.g. persist while updating)
  kTimeout = 22,          // an expected message or transfer did not arrive
};

// A short constant name for logs and error messages (never null).
const char* error_name(Error e);

template <typename T>
class Result {
 public:
  Result(const T& value) : ok_(true) { new (&storage_) T(value); }  // NOLINT: implicit by design
  Result(T&& value) : ok_(true) { new (&storage_) T(std::move(value)); }  // NOLINT
  Result(Error error) : ok_(false), error_(error) {}  // NOLINT
  Result(const Result& o) : ok_(o.ok_), error_(o.error_) {
    if (ok_) new (&storage_) T(o.value());
  }
  Result& operator=(const Result& o) {
    if (this != &o) {
      reset();
      ok_ = o.ok_;
      error_ = o.error_;
      if (ok_) new (&storage_) T(o.value());
    }
    return *this;
  }
  ~Result() { reset(); }

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  Error error() const { return ok_ ? Error::kNone : error_; }
  // Through void*: storage_ is aligned for T, which -Wcast-align cannot see on Cortex-M.
  const T& value() const { return *std::launder(static_cast<const T*>(static_cast<const void*>(&storage_))); }
  T& value() { return *std::launder(static_cast<T*>(static_cast<void*>(&storage_))); }
  const T& operator*() const { return value(); }
  T& operator*() { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  void reset() {
    if (ok_) value().~T();
    ok_ = false;
  }
  bool ok_;
  Error error_ = Error::kNone;
  alignas(T) unsigned char storage_[sizeof(T)];
};

// Status: success or an error, nothing else.
class Status {
 public:
  Status() = default;
  Status(Error e) : error_(e) {}  // NOLINT: implicit by design
  bool ok() const { return error_ == Error::kNone; }
  explicit operator bool() const { return ok(); }
  Error error() const { return error_; }

 private:
  Error error_ = Error::kNone;
};

}  // namespace tetrapulse::protocol
