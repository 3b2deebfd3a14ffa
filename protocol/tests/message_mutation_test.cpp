// Every truncation and every single-bit flip of every message vector either decodes to a
// valid message that re-encodes to exactly the same bytes, or is refused with an error.
// (Under the asan preset this also proves no read outside the input.)
#include <gtest/gtest.h>

#include <map>

#include "hex_vectors.hpp"
#include "message_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

std::vector<HexRecord> message_vectors() {
  std::vector<HexRecord> records;
  for (const char* folder : {"/messages", "/messages/malformed"}) {
    const auto files = read_hex_folder(vectors_dir() + folder);
    EXPECT_TRUE(files.has_value()) << (files ? "" : files.error());
    if (!files) continue;
    for (const HexFile& file : *files) records.insert(records.end(), file.records.begin(), file.records.end());
  }
  return records;
}

struct Tally {
  int decoded = 0;
  std::map<Error, int> refused;
};

// Decodes `bytes`; what decodes must be valid and canonical.
void check(const std::vector<uint8_t>& bytes, const std::string& what, Tally* tally) {
  // A copy of exactly `bytes.size()` so ASan catches any read past the end.
  const std::unique_ptr<uint8_t[]> exact(new uint8_t[bytes.size() + 1]);
  std::copy(bytes.begin(), bytes.end(), exact.get());
  const auto decoded = decode(ByteView{exact.get(), bytes.size()});
  if (!decoded.ok()) {
    EXPECT_NE(decoded.error(), Error::kNone) << what;
    ++tally->refused[decoded.error()];
    return;
  }
  ++tally->decoded;
  EXPECT_TRUE(validate(*decoded).ok()) << what;
  EXPECT_EQ(to_hex(encode_bytes(*decoded)), to_hex(bytes)) << what;
}

TEST(MessageMutation, EveryTruncationDecodesOrFails) {
  Tally tally;
  for (const HexRecord& r : message_vectors()) {
    for (size_t n = 0; n < r.bytes.size(); ++n) {
      check(std::vector<uint8_t>(r.bytes.begin(), r.bytes.begin() + static_cast<long>(n)),
            r.origin + " cut to " + std::to_string(n), &tally);
    }
  }
  // Only malformed "trailing" vectors have prefixes that are whole messages.
  EXPECT_LE(tally.decoded, 3);
  EXPECT_GT(tally.refused[Error::kTruncated], 1000);
}

TEST(MessageMutation, EverySingleBitFlipDecodesOrFails) {
  Tally tally;
  size_t flips = 0;
  for (const HexRecord& r : message_vectors()) {
    for (size_t bit = 0; bit < r.bytes.size() * 8; ++bit) {
      auto bytes = r.bytes;
      bytes[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      check(bytes, r.origin + " bit " + std::to_string(bit), &tally);
      ++flips;
    }
  }
  // Flips in free-valued fields (times, counters, chunk data) decode; flips in the envelope,
  // enums and counts are refused.
  EXPECT_GT(tally.decoded, 0);
  EXPECT_LT(tally.decoded, static_cast<int>(flips));
  EXPECT_GT(tally.refused[Error::kBadVersion], 0);
  EXPECT_GT(tally.refused[Error::kUnknownMessage], 0);
  EXPECT_GT(tally.refused[Error::kBadValue], 0);
  EXPECT_GT(tally.refused[Error::kBadLength], 0);
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
