// Every message type, with random values anywhere in its fields' ranges, encodes, decodes
// to the same message, and re-encodes to the same bytes.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include "message_generators.hpp"
#include "message_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

// One property per check, over the bodies of one type: the typed tests below
// only name the type (a lambda per type would instantiate rapidcheck per type).
bool survives_encode_decode_encode(MessageType type) {
  return rc::check(message_name(type), [type](uint8_t seq) {
    const Message m{seq, *body_of_type(type)};
    Error error = Error::kNone;
    const auto bytes = encode_bytes(m, &error);
    RC_ASSERT(error == Error::kNone);
    RC_ASSERT(bytes.size() <= kMaxMessageSize);
    RC_ASSERT(bytes[1] == static_cast<uint8_t>(type));
    const auto decoded = decode(view(bytes));
    RC_ASSERT(decoded.ok());
    RC_ASSERT(decoded->seq == seq);
    RC_ASSERT(text(*decoded) == text(m));
    RC_ASSERT(encode_bytes(*decoded) == bytes);
  });
}

// An encoder given too little room says so at every size short of the message.
bool refuses_every_too_small_buffer(MessageType type) {
  return rc::check(message_name(type), [type] {
    const Message m{0, *body_of_type(type)};
    const size_t size = encode_bytes(m).size();
    std::vector<uint8_t> buffer(size);
    for (size_t capacity = 0; capacity < size; ++capacity) {
      ByteWriter out(buffer.data(), capacity);
      RC_ASSERT(encode(m, out).error() == Error::kBufferTooSmall);
      RC_ASSERT(out.size() <= capacity);
    }
  });
}

template <class T>
class MessageRoundTrip : public ::testing::Test {};
TYPED_TEST_SUITE(MessageRoundTrip, BodyTypes, BodyTypeName);

TYPED_TEST(MessageRoundTrip, RandomFieldsSurviveEncodeDecodeEncode) {
  EXPECT_TRUE(survives_encode_decode_encode(TypeParam::kType));
}

TYPED_TEST(MessageRoundTrip, EveryTooSmallBufferIsRefused) {
  EXPECT_TRUE(refuses_every_too_small_buffer(TypeParam::kType));
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
