#pragma once
// The golden transport vectors of protocol/vectors/{uart,usb,can} as the host tests use
// them: a message and the bytes a transport puts on the wire for it.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vector_file.hpp"

namespace tetrapulse::host::testing {

struct WireVector {
  std::string file;
  std::vector<uint8_t> message;
  std::vector<uint8_t> wire;  // the UART frame (delimiter included) or the USB bulk transfer
};

// Every vector of `part` ("uart": message/frame, "usb" with prefix "bulk_": message/transfer).
inline std::vector<WireVector> wire_vectors(const std::string& part, const std::string& prefix,
                                            const std::string& wire_label) {
  std::vector<WireVector> out;
  auto files = protocol::testing::read_vector_dir(protocol::testing::vectors_dir(part), prefix);
  EXPECT_TRUE(files.has_value()) << (files ? "" : files.error());
  if (!files) return out;
  for (const protocol::testing::VectorFile& f : *files) {
    const auto* message = f.first("message");
    const auto* wire = f.first(wire_label);
    EXPECT_TRUE(message && wire) << f.path;
    if (message && wire) out.push_back(WireVector{f.path, message->bytes, wire->bytes});
  }
  return out;
}

}  // namespace tetrapulse::host::testing
