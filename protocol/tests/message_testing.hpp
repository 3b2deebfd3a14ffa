#pragma once
// Host-side conveniences for protocol tests: messages as text and byte vectors.
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol::testing {

// format_message() as a std::string: equal texts mean equal messages (every field is printed).
inline std::string text(const Message& m) {
  std::string s(format_message(m, nullptr, 0) + 1, '\0');
  s.resize(format_message(m, s.data(), s.size()));
  return s;
}

inline ByteView view(const std::vector<uint8_t>& bytes) { return ByteView{bytes.data(), bytes.size()}; }

// The encoding of `m`, or empty with `*error` set.
inline std::vector<uint8_t> encode_bytes(const Message& m, Error* error = nullptr) {
  std::vector<uint8_t> buffer(kMaxMessageSize);
  ByteWriter out(buffer.data(), buffer.size());
  const Status s = encode(m, out);
  if (error != nullptr) *error = s.error();
  if (!s.ok()) return {};
  buffer.resize(out.size());
  return buffer;
}

// A code from its '0'/'1' string, character i -> bit i.
inline Code code_from_string(std::string_view s) {
  Code code;
  code.length = static_cast<uint8_t>(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '1') code.bits |= uint64_t{1} << i;
  }
  return code;
}

}  // namespace tetrapulse::protocol::testing

namespace tetrapulse::protocol {
// How rapidcheck and GoogleTest show a message in a failure.
inline void showValue(const Message& m, std::ostream& os) { os << testing::text(m); }
inline void PrintTo(const Message& m, std::ostream* os) { *os << testing::text(m); }
}  // namespace tetrapulse::protocol
