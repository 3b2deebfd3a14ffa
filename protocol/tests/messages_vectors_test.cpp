// The golden vectors of protocol/vectors/messages decode to the messages their comments
// describe and re-encode to the same bytes; every malformed vector fails with the Error
// its error= attribute names.
#include <gtest/gtest.h>

#include <set>

#include "golden_messages.hpp"
#include "message_testing.hpp"
#include "vector_cases.hpp"

namespace tetrapulse::protocol::testing {
namespace {

class GoldenMessage : public ::testing::TestWithParam<VectorCase> {};

TEST_P(GoldenMessage, DecodesToItsFieldsAndReencodesIdentically) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  const auto golden = golden_messages();
  const auto expected = golden.find(c.key);
  ASSERT_NE(expected, golden.end()) << c.record.origin << ": no expected message for " << c.key;

  const auto decoded = decode(view(c.record.bytes));
  ASSERT_TRUE(decoded.ok()) << c.record.origin << ": " << error_name(decoded.error());
  EXPECT_EQ(text(*decoded), text(expected->second)) << c.record.origin;

  Error error = Error::kNone;
  EXPECT_EQ(to_hex(encode_bytes(expected->second, &error)), to_hex(c.record.bytes)) << c.record.origin;
  EXPECT_EQ(error, Error::kNone);
}

INSTANTIATE_TEST_SUITE_P(Vectors, GoldenMessage, ::testing::ValuesIn(vector_cases("messages")), case_name);

// Every expected message has its vector, and every defined type has one.
TEST(GoldenMessages, CoverEveryMessageType) {
  std::set<std::string> keys;
  for (const VectorCase& c : vector_cases("messages")) keys.insert(c.key);
  std::set<int> covered;
  for (const auto& [key, message] : golden_messages()) {
    EXPECT_EQ(keys.count(key), 1u) << "no vector for " << key;
    covered.insert(static_cast<int>(message.type()));
  }
  for (int t = 0; t < 256; ++t) {
    if (is_defined(static_cast<MessageType>(t))) {
      EXPECT_EQ(covered.count(t), 1u) << "no golden vector of " << message_name(static_cast<MessageType>(t));
    }
  }
}

class MalformedMessage : public ::testing::TestWithParam<VectorCase> {};

TEST_P(MalformedMessage, FailsWithTheNamedError) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  const Error expected = expected_error(c.record);
  ASSERT_NE(expected, Error::kNone) << c.record.origin << ": the record has no error=<name> of a defined Error";
  const auto decoded = decode(view(c.record.bytes));
  EXPECT_EQ(decoded.error(), expected) << c.record.origin << " (" << c.record.description << "): got "
                                       << error_name(decoded.error());
}

INSTANTIATE_TEST_SUITE_P(Vectors, MalformedMessage, ::testing::ValuesIn(vector_cases("messages/malformed")),
                         case_name);

}  // namespace
}  // namespace tetrapulse::protocol::testing
