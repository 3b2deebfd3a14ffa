// Every message type, with random values anywhere in its fields' ranges, encodes, decodes
// to the same message, and re-encodes to the same bytes.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include "message_generators.hpp"
#include "message_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

template <class T>
class MessageRoundTrip : public ::testing::Test {};
TYPED_TEST_SUITE(MessageRoundTrip, BodyTypes, BodyTypeName);

TYPED_TEST(MessageRoundTrip, RandomFieldsSurviveEncodeDecodeEncode) {
  const bool ok = rc::check(message_name(TypeParam::kType), [](uint8_t seq, const TypeParam& body) {
    const Message m{seq, body};
    Error error = Error::kNone;
    const auto bytes = encode_bytes(m, &error);
    RC_ASSERT(error == Error::kNone);
    RC_ASSERT(bytes.size() <= kMaxMessageSize);
    RC_ASSERT(bytes[1] == static_cast<uint8_t>(TypeParam::kType));
    const auto decoded = decode(view(bytes));
    RC_ASSERT(decoded.ok());
    RC_ASSERT(decoded->seq == seq);
    RC_ASSERT(text(*decoded) == text(m));
    RC_ASSERT(encode_bytes(*decoded) == bytes);
  });
  EXPECT_TRUE(ok);
}

// An encoder given too little room says so at every size short of the message.
TYPED_TEST(MessageRoundTrip, EveryTooSmallBufferIsRefused) {
  const bool ok = rc::check(message_name(TypeParam::kType), [](const TypeParam& body) {
    const Message m{0, body};
    const size_t size = encode_bytes(m).size();
    std::vector<uint8_t> buffer(size);
    for (size_t capacity = 0; capacity < size; ++capacity) {
      ByteWriter out(buffer.data(), capacity);
      RC_ASSERT(encode(m, out).error() == Error::kBufferTooSmall);
      RC_ASSERT(out.size() <= capacity);
    }
  });
  EXPECT_TRUE(ok);
}

// The generator over all types (used by transports' tests) yields only encodable messages.
TEST(MessageGenerator, EveryGeneratedMessageEncodes) {
  EXPECT_TRUE(rc::check("any message", [](const Message& m) {
    RC_ASSERT(validate(m).ok());
    RC_ASSERT(!encode_bytes(m).empty());
  }));
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
