#pragma once
// The golden transport vectors of protocol/vectors/{uart,usb} as the host tests use them: a
// message and the bytes a transport puts on the wire for it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "transport_vectors.hpp"

namespace tetrapulse::host::testing {

struct WireVector {
  std::string file;
  std::vector<uint8_t> message;
  std::vector<uint8_t> wire;  // the UART frame (delimiter included) or the USB bulk transfer
};

// Every vector of vectors/<part> whose file name starts with `prefix`: its [message] and its
// `wire_record` ("uart": [frame]; "usb" with prefix "bulk_": [transfer]).
inline std::vector<WireVector> wire_vectors(const std::string& part, const std::string& prefix,
                                            const std::string& wire_record) {
  std::vector<WireVector> out;
  auto files = protocol::testing::read_vectors(part, prefix);
  EXPECT_TRUE(files.has_value()) << (files ? "" : files.error());
  if (!files) return out;
  for (const protocol::testing::HexFile& f : *files) {
    const auto* message = f.find("message");
    const auto* wire = f.find(wire_record);
    EXPECT_TRUE(message && wire) << f.path;
    if (message && wire) out.push_back(WireVector{f.path, message->bytes, wire->bytes});
  }
  return out;
}

}  // namespace tetrapulse::host::testing
