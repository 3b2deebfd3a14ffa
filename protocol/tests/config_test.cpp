// The Config on its own, as flash stores it: size, defaults, validation, round trip.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include "message_generators.hpp"
#include "message_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

std::vector<uint8_t> encode_config_bytes(const Config& c, Error* error) {
  std::vector<uint8_t> buffer(kConfigSize + 8);
  ByteWriter out(buffer.data(), buffer.size());
  *error = encode_config(c, out).error();
  buffer.resize(out.size());
  return buffer;
}

std::string config_text(const Config& c) { return text(Message{0, ConfigReport{c}}); }

TEST(Config, DefaultIsValidAndMatchesTheSpec) {
  const Config c = default_config();
  EXPECT_TRUE(validate(c).ok());
  EXPECT_EQ(c.node_id, 1);
  for (const Code& code : c.codes) EXPECT_EQ(code.length, 0);  // markers lit constantly
  EXPECT_EQ(c.bit_period_ns, 10'000'000u);
  EXPECT_EQ(c.sync_source, SyncSource::kNone);
}

TEST(Config, EncodesToKConfigSizeAndBack) {
  EXPECT_TRUE(rc::check("config round trip", [](const Config& c) {
    Error error = Error::kNone;
    const auto bytes = encode_config_bytes(c, &error);
    RC_ASSERT(error == Error::kNone);
    RC_ASSERT(bytes.size() == kConfigSize);
    const auto decoded = decode_config(view(bytes));
    RC_ASSERT(decoded.ok());
    RC_ASSERT(config_text(*decoded) == config_text(c));
  }));
}

TEST(Config, DecodeNeedsExactlyKConfigSizeBytes) {
  Error error = Error::kNone;
  auto bytes = encode_config_bytes(default_config(), &error);
  ASSERT_EQ(error, Error::kNone);
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_EQ(decode_config(ByteView{bytes.data(), n}).error(), Error::kTruncated) << n;
  }
  bytes.push_back(0);
  EXPECT_EQ(decode_config(view(bytes)).error(), Error::kTrailingBytes);
}

TEST(Config, BitPeriodAndEdgePeriodHaveA10usFloor) {
  Config c = default_config();
  c.bit_period_ns = kMinBitPeriodNs;
  c.gpio_edge_period_ns = kMinGpioEdgePeriodNs;
  EXPECT_TRUE(validate(c).ok());
  c.bit_period_ns = kMinBitPeriodNs - 1;
  EXPECT_EQ(validate(c).error(), Error::kBadValue);
  c.bit_period_ns = kMinBitPeriodNs;
  c.gpio_edge_period_ns = kMinGpioEdgePeriodNs - 1;
  EXPECT_EQ(validate(c).error(), Error::kBadValue);
}

TEST(Config, NodeIdIs1To254) {
  Config c = default_config();
  for (int id = 0; id < 256; ++id) {
    c.node_id = static_cast<uint8_t>(id);
    EXPECT_EQ(validate(c).ok(), id >= 1 && id <= 254) << id;
  }
}

// Bit i of `bits` is character i of the code string; a 64-bit code uses every bit.
TEST(Config, CodeBitsFollowTheStringLsbFirst) {
  const Code c = code_from_string("1101001110");
  EXPECT_EQ(c.bits, 0x1CBu);
  EXPECT_TRUE(c.bit(0));
  EXPECT_FALSE(c.bit(2));
  EXPECT_FALSE(c.bit(9));
  Config config = default_config();
  config.codes[0] = code_from_string(std::string(64, '1'));
  EXPECT_TRUE(validate(config).ok());
  EXPECT_EQ(config.codes[0].bits, UINT64_MAX);
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
