#include "tetrapulse/protocol/cobs.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes encode(const Bytes& in) {
  Bytes out(cobs_max_encoded_size(in.size()));
  const Result<size_t> n = cobs_encode(ByteView{in.data(), in.size()}, out.data(), out.size());
  EXPECT_TRUE(n.ok());
  out.resize(n.ok() ? *n : 0);
  return out;
}

Result<Bytes> decode(const Bytes& in) {
  Bytes out(in.size() + 1);
  const Result<size_t> n = cobs_decode(ByteView{in.data(), in.size()}, out.data(), out.size());
  if (!n) return n.error();
  out.resize(*n);
  return out;
}

Bytes range(int first, int last) {  // first..last inclusive
  Bytes b;
  for (int i = first; i <= last; ++i) b.push_back(static_cast<uint8_t>(i));
  return b;
}

Bytes cat(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The worked examples of the COBS literature (Cheshire & Baker; also on Wikipedia).
TEST(Cobs, PublishedExamples) {
  const std::vector<std::pair<Bytes, Bytes>> cases = {
      {{}, {0x01}},
      {{0x00}, {0x01, 0x01}},
      {{0x00, 0x00}, {0x01, 0x01, 0x01}},
      {{0x00, 0x11, 0x00}, {0x01, 0x02, 0x11, 0x01}},
      {{0x11, 0x22, 0x00, 0x33}, {0x03, 0x11, 0x22, 0x02, 0x33}},
      {{0x11, 0x22, 0x33, 0x44}, {0x05, 0x11, 0x22, 0x33, 0x44}},
      {{0x11, 0x00, 0x00, 0x00}, {0x02, 0x11, 0x01, 0x01, 0x01}},
      {range(1, 254), cat({0xFF}, range(1, 254))},
      {range(0, 254), cat({0x01, 0xFF}, range(1, 254))},
      {range(1, 255), cat(cat({0xFF}, range(1, 254)), {0x02, 0xFF})},
      {cat(range(2, 255), {0x00}), cat(cat({0xFF}, range(2, 255)), {0x01, 0x01})},
      {cat(range(3, 255), {0x00, 0x01}), cat(cat({0xFE}, range(3, 255)), {0x02, 0x01})},
  };
  for (const auto& [plain, encoded] : cases) {
    EXPECT_EQ(encode(plain), encoded);
    const Result<Bytes> back = decode(encoded);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, plain);
  }
}

TEST(Cobs, AcceptsTrailingEmptyBlockAfterFullBlock) {
  const Result<Bytes> back = decode(cat(cat({0xFF}, range(1, 254)), {0x01}));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, range(1, 254));
}

TEST(Cobs, MaxEncodedSizeIsReachedByNonZeroData) {
  for (size_t n = 0; n < 1100; ++n) {
    const Bytes ones(n, 0x01);
    EXPECT_EQ(encode(ones).size(), cobs_max_encoded_size(n)) << n;
  }
}

TEST(Cobs, RejectsBrokenEncodings) {
  EXPECT_EQ(decode({}).error(), Error::kBadFraming);
  EXPECT_EQ(decode({0x03, 0x11}).error(), Error::kBadFraming);        // block cut short
  EXPECT_EQ(decode({0x02, 0x00, 0x01}).error(), Error::kBadFraming);  // a zero inside
  uint8_t out[1];
  const uint8_t in[] = {0x03, 0x11, 0x22};
  EXPECT_EQ(cobs_decode(ByteView{in, 3}, out, 1).error(), Error::kBufferTooSmall);
  EXPECT_EQ(cobs_encode(ByteView{in, 3}, out, 1).error(), Error::kBufferTooSmall);
}

RC_GTEST_PROP(Cobs, RoundTripsWithoutZeros, (const Bytes& plain)) {
  const Bytes encoded = encode(plain);
  RC_ASSERT(encoded.size() <= cobs_max_encoded_size(plain.size()));
  for (uint8_t b : encoded) RC_ASSERT(b != 0);
  const Result<Bytes> back = decode(encoded);
  RC_ASSERT(back.ok());
  RC_ASSERT(*back == plain);
}

}  // namespace
}  // namespace tetrapulse::protocol
