// Every way a message can be malformed, swept over all the bytes where it can happen:
// the decoder names the error, the encoder refuses to write what the decoder would refuse.
#include <gtest/gtest.h>

#include <functional>

#include "golden_messages.hpp"
#include "message_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

std::vector<uint8_t> golden(const std::string& key) { return encode_bytes(golden_messages().at(key)); }

Error decode_error(const std::vector<uint8_t>& bytes) { return decode(view(bytes)).error(); }

// Where a body ends with a count and the items it counts (SPEC.md §2.1), the offset
// after that count; 0 for other messages.
size_t tail_start(MessageType type) {
  if (type == MessageType::kUpdateChunk) return kMessageHeaderSize + 4 + 2;
  if (type == MessageType::kLedLog) return kMessageHeaderSize + 4 + 1;
  return 0;
}

TEST(MessageDecode, EmptyInputIsTruncated) { EXPECT_EQ(decode(ByteView{nullptr, 0}).error(), Error::kTruncated); }

TEST(MessageDecode, EveryVersionButOneIsRefused) {
  auto bytes = golden("identify");
  for (int v = 0; v < 256; ++v) {
    bytes[0] = static_cast<uint8_t>(v);
    EXPECT_EQ(decode_error(bytes), v == kProtocolVersion ? Error::kNone : Error::kBadVersion) << v;
  }
}

// Type codes: the defined ones decode (here with an empty body: some then lack fields),
// every other is kUnknownMessage, even with no seq after it.
TEST(MessageDecode, EveryUndefinedTypeIsUnknown) {
  int defined = 0;
  for (int t = 0; t < 256; ++t) {
    const auto type = static_cast<MessageType>(t);
    const Error with_seq = decode_error({kProtocolVersion, static_cast<uint8_t>(t), 0});
    const Error without_seq = decode_error({kProtocolVersion, static_cast<uint8_t>(t)});
    if (is_defined(type)) {
      ++defined;
      EXPECT_NE(with_seq, Error::kUnknownMessage) << t;
      EXPECT_EQ(without_seq, Error::kTruncated) << t;
      EXPECT_STRNE(message_name(type), "unknown") << t;
    } else {
      EXPECT_EQ(with_seq, Error::kUnknownMessage) << t;
      EXPECT_EQ(without_seq, Error::kUnknownMessage) << t;
      EXPECT_STREQ(message_name(type), "unknown") << t;
    }
  }
  EXPECT_EQ(defined, static_cast<int>(std::variant_size_v<Body>));
}

// Cut every golden message at every byte: kTruncated, or kBadLength once a count has been
// read that the remaining bytes cannot satisfy.
TEST(MessageDecode, TruncatedAtEveryByte) {
  for (const auto& [key, message] : golden_messages()) {
    const auto bytes = encode_bytes(message);
    const size_t tail = tail_start(message.type());
    for (size_t n = 0; n < bytes.size(); ++n) {
      const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<long>(n));
      const Error expected = (tail != 0 && n >= tail) ? Error::kBadLength : Error::kTruncated;
      EXPECT_EQ(decode_error(prefix), expected) << key << " cut to " << n << " of " << bytes.size();
    }
  }
}

TEST(MessageDecode, TrailingBytesAfterEveryMessage) {
  for (const auto& [key, message] : golden_messages()) {
    for (uint8_t extra : {0x00, 0x5A, 0xFF}) {
      auto bytes = encode_bytes(message);
      bytes.push_back(extra);
      const Error expected = tail_start(message.type()) != 0 ? Error::kBadLength : Error::kTrailingBytes;
      EXPECT_EQ(decode_error(bytes), expected) << key;
    }
  }
}

// Errors are reported in the order of SPEC.md §2.1: fields read, values, leftovers.
TEST(MessageDecode, ReportsTheFirstErrorInSpecOrder) {
  auto bad_pattern = golden("identify");
  bad_pattern[3] = 9;
  auto bad_and_long = bad_pattern;
  bad_and_long.push_back(0);
  EXPECT_EQ(decode_error(bad_and_long), Error::kBadValue);
  const std::vector<uint8_t> bad_and_short(bad_pattern.begin(), bad_pattern.end() - 1);
  EXPECT_EQ(decode_error(bad_and_short), Error::kTruncated);
  auto bad_version_and_type = golden("identify");
  bad_version_and_type[0] = 2;
  bad_version_and_type[1] = 0x3F;
  EXPECT_EQ(decode_error(bad_version_and_type), Error::kBadVersion);
}

std::vector<uint8_t> chunk_bytes(uint16_t length_field, size_t data_bytes) {
  std::vector<uint8_t> b = {kProtocolVersion, static_cast<uint8_t>(MessageType::kUpdateChunk), 1, 0, 0, 0, 0,
                            static_cast<uint8_t>(length_field), static_cast<uint8_t>(length_field >> 8)};
  b.resize(b.size() + data_bytes, 0xA5);
  return b;
}

// Where decoding stopped, as ErrorResponse.detail reports it (SPEC.md §3).
size_t stopped_at(const std::vector<uint8_t>& bytes, Error expected) {
  size_t at = 9999;
  EXPECT_EQ(decode(view(bytes), &at).error(), expected);
  return at;
}

TEST(MessageDecode, StopsAtTheOffsetErrorResponseDetailReports) {
  const auto identify = golden("identify");  // 01 05 05 | pattern | duration_ms (2 bytes)
  auto bad_version = identify;
  bad_version[0] = 2;
  EXPECT_EQ(stopped_at(bad_version, Error::kBadVersion), 0u);
  EXPECT_EQ(stopped_at({}, Error::kTruncated), 0u);
  EXPECT_EQ(stopped_at({1}, Error::kTruncated), 1u);
  EXPECT_EQ(stopped_at({1, 0x3F}, Error::kUnknownMessage), 1u);
  EXPECT_EQ(stopped_at({1, 0x05}, Error::kTruncated), 2u);
  // Cut inside duration_ms: the field that runs past the end starts at 4.
  EXPECT_EQ(stopped_at({identify.begin(), identify.end() - 1}, Error::kTruncated), 4u);
  auto bad_pattern = identify;
  bad_pattern[3] = 9;
  EXPECT_EQ(stopped_at(bad_pattern, Error::kBadValue), identify.size());
  auto longer = identify;
  longer.push_back(0);
  EXPECT_EQ(stopped_at(longer, Error::kTrailingBytes), identify.size());
  // UpdateChunk: 3 envelope + offset (4) + length (2); a count the data disagrees with.
  EXPECT_EQ(stopped_at(chunk_bytes(5, 4), Error::kBadLength), 9u);
  EXPECT_EQ(stopped_at(chunk_bytes(300, 300), Error::kBadLength), 9u);
  EXPECT_EQ(stopped_at(chunk_bytes(0, 0), Error::kBadLength), 9u);  // length 0: a value check at the end
  // Success leaves it alone.
  size_t untouched = 77;
  EXPECT_TRUE(decode(view(identify), &untouched).ok());
  EXPECT_EQ(untouched, 77u);
}

// Every cut of every golden message stops inside the bytes it was given.
TEST(MessageDecode, StopsWithinTheInputForEveryCut) {
  for (const auto& [key, message] : golden_messages()) {
    const auto bytes = encode_bytes(message);
    for (size_t n = 0; n < bytes.size(); ++n) {
      size_t at = 9999;
      EXPECT_FALSE(decode(ByteView{bytes.data(), n}, &at).ok());
      EXPECT_LE(at, n) << key << " cut to " << n;
    }
  }
}

// One byte of a golden message swept over 0..255: decodes exactly when `valid` says so,
// else fails with `error`.
struct FieldSweep {
  const char* what;
  std::string key;
  size_t offset;
  std::function<bool(int)> valid;
  Error error;
};

bool up_to(int v, int max) { return v <= max; }

TEST(MessageDecode, EnumAndRangeFieldsAcceptExactlyTheirValues) {
  constexpr size_t h = kMessageHeaderSize;
  constexpr size_t config_sync = h + 1 + 2 + 36 + 1 + 2 + 4 + 8 + 2 + 2;  // sync_source in a Config body
  const std::vector<FieldSweep> sweeps = {
      {"identify.pattern", "identify", h, [](int v) { return up_to(v, 3); }, Error::kBadValue},
      {"reboot.mode", "reboot", h, [](int v) { return up_to(v, 1); }, Error::kBadValue},
      {"config.node_id", "set_config", h, [](int v) { return v >= 1 && v <= 254; }, Error::kBadValue},
      {"config.modulation", "set_config", h + 1 + 2 + 36, [](int v) { return up_to(v, 2); }, Error::kBadValue},
      {"config.sync_source", "set_config", config_sync, [](int v) { return up_to(v, 2); }, Error::kBadValue},
      {"config.gpio_edge", "set_config", config_sync + 1, [](int v) { return up_to(v, 1); }, Error::kBadValue},
      {"config.gpio_edge_numbering", "config_report", h + kConfigSize - 1, [](int v) { return up_to(v, 1); },
       Error::kBadValue},
      {"status.sync_state", "status_report", h, [](int v) { return up_to(v, 3); }, Error::kBadValue},
      {"status.sync_source", "status_report", h + 1, [](int v) { return up_to(v, 2); }, Error::kBadValue},
      {"status.can_bus_off", "status_report", h + 26, [](int v) { return up_to(v, 1); }, Error::kBadValue},
      {"status.last_error", "status_report", h + 31, [](int) { return true; }, Error::kNone},
      {"status.update_state", "status_report", h + 32, [](int v) { return up_to(v, 3); }, Error::kBadValue},
      {"info.hw_model", "info", h + 1, [](int v) { return v >= 1 && v <= 3; }, Error::kBadValue},
      {"info.node_id", "info", h + 36, [](int v) { return v >= 1 && v <= 254; }, Error::kBadValue},
      {"info.max_code_length", "info", h + 38, [](int v) { return v >= 1 && v <= 64; }, Error::kBadValue},
      {"ack.request_type", "ack", h, [](int v) { return is_request(static_cast<MessageType>(v)) &&
                                                        is_defined(static_cast<MessageType>(v)); },
       Error::kBadValue},
      {"error_response.request_type", "error_response", h, [](int) { return true; }, Error::kNone},
      {"error_response.error", "error_response", h + 1, [](int v) { return v != 0; }, Error::kBadValue},
      {"led_log.entries[0].marker", "led_log.two", h + 5 + 12, [](int v) { return up_to(v, 3); },
       Error::kBadValue},
      {"led_log.entries[1].marker", "led_log.two", h + 5 + 15 + 12, [](int v) { return up_to(v, 3); },
       Error::kBadValue},
  };
  for (const FieldSweep& s : sweeps) {
    auto bytes = golden(s.key);
    ASSERT_LT(s.offset, bytes.size()) << s.what;
    for (int v = 0; v < 256; ++v) {
      bytes[s.offset] = static_cast<uint8_t>(v);
      EXPECT_EQ(decode_error(bytes), s.valid(v) ? Error::kNone : s.error) << s.what << " = " << v;
    }
  }
}

// A code must not have bits at or beyond its length, for every length and bit.
TEST(MessageDecode, CodeBitsBeyondTheLengthAreRefused) {
  const auto base = golden("set_config");
  constexpr size_t kCode0 = kMessageHeaderSize + 1 + 2;  // codes[0].length; its bits follow
  int refused = 0;
  for (int length = 0; length <= 64; ++length) {
    for (int bit = 0; bit < 64; ++bit) {
      auto bytes = base;
      bytes[kCode0] = static_cast<uint8_t>(length);
      for (size_t i = 0; i < 8; ++i) bytes[kCode0 + 1 + i] = 0;
      bytes[kCode0 + 1 + static_cast<size_t>(bit / 8)] = static_cast<uint8_t>(1u << (bit % 8));
      const bool beyond = bit >= length;
      EXPECT_EQ(decode_error(bytes), beyond ? Error::kBadValue : Error::kNone) << length << " " << bit;
      refused += beyond;
    }
  }
  EXPECT_EQ(refused, 64 * 65 / 2);
  auto too_long = base;
  too_long[kCode0] = 65;
  EXPECT_EQ(decode_error(too_long), Error::kBadValue);
}

TEST(MessageDecode, ChunkLengthMustBe1To256AndMatchTheData) {
  for (size_t n = 0; n <= 300; ++n) {
    const bool valid = n >= 1 && n <= kMaxUpdateChunk;
    EXPECT_EQ(decode_error(chunk_bytes(static_cast<uint16_t>(n), n)), valid ? Error::kNone : Error::kBadLength) << n;
    EXPECT_EQ(decode_error(chunk_bytes(static_cast<uint16_t>(n), n + 1)), Error::kBadLength) << n;
    if (n > 0) {
      EXPECT_EQ(decode_error(chunk_bytes(static_cast<uint16_t>(n), n - 1)), Error::kBadLength) << n;
    }
  }
  EXPECT_EQ(decode_error(chunk_bytes(0xFFFF, 0xFFFF)), Error::kBadLength);
}

TEST(MessageDecode, LedLogCountMustBeAtMost16AndMatchTheEntries) {
  constexpr size_t kEntry = 15;
  for (int count = 0; count <= 255; ++count) {
    std::vector<uint8_t> b = {kProtocolVersion, static_cast<uint8_t>(MessageType::kLedLog), 1, 0, 0, 0, 0,
                              static_cast<uint8_t>(count)};
    b.resize(b.size() + static_cast<size_t>(count) * kEntry, 0);
    EXPECT_EQ(decode_error(b), count <= 16 ? Error::kNone : Error::kBadLength) << count;
    b.push_back(0);
    EXPECT_EQ(decode_error(b), Error::kBadLength) << count;
  }
}

// What the decoder refuses, the encoder refuses too, and writes nothing.
TEST(MessageEncode, RefusesInvalidFieldsAndWritesNothing) {
  Config bad_node = default_config();
  bad_node.node_id = 0;
  Config bad_bits = default_config();
  bad_bits.codes[1] = code_from_string("101");
  bad_bits.codes[1].bits |= uint64_t{1} << 3;
  Config bad_period = default_config();
  bad_period.bit_period_ns = kMinBitPeriodNs - 1;
  Config bad_edge_period = default_config();
  bad_edge_period.gpio_edge_period_ns = 0;
  Config bad_modulation = default_config();
  bad_modulation.modulation = static_cast<Modulation>(3);
  UpdateChunk empty_chunk;
  UpdateChunk long_chunk;
  long_chunk.length = kMaxUpdateChunk + 1;
  LedLog long_log;
  long_log.count = kMaxLedLogEntries + 1;
  LedLog bad_marker;
  bad_marker.count = 1;
  bad_marker.entries[0].marker = 4;
  Info bad_info;
  bad_info.hw_model = static_cast<HwModel>(0);
  StatusReport bad_status;
  bad_status.can_bus_off = 2;

  const std::vector<std::pair<Message, Error>> cases = {
      {{1, SetConfig{bad_node}}, Error::kBadValue},
      {{1, SetConfig{bad_bits}}, Error::kBadValue},
      {{1, SetConfig{bad_period}}, Error::kBadValue},
      {{1, ConfigReport{bad_edge_period}}, Error::kBadValue},
      {{1, ConfigReport{bad_modulation}}, Error::kBadValue},
      {{1, Identify{static_cast<IdentifyPattern>(4), 0}}, Error::kBadValue},
      {{1, Reboot{static_cast<RebootMode>(2)}}, Error::kBadValue},
      {{1, UpdateBegin{63, 0, 0}}, Error::kBadValue},
      {{1, empty_chunk}, Error::kBadLength},
      {{1, long_chunk}, Error::kBadLength},
      {{1, long_log}, Error::kBadLength},
      {{1, bad_marker}, Error::kBadValue},
      {{1, bad_info}, Error::kBadValue},
      {{1, bad_status}, Error::kBadValue},
      {{1, Ack{MessageType::kInfo, 0}}, Error::kBadValue},
      {{1, ErrorResponse{MessageType::kGetInfo, Error::kNone, 0}}, Error::kBadValue},
  };
  for (const auto& [message, expected] : cases) {
    uint8_t buffer[kMaxMessageSize];
    ByteWriter out(buffer, sizeof(buffer));
    EXPECT_EQ(encode(message, out).error(), expected) << text(message);
    EXPECT_EQ(validate(message).error(), expected) << text(message);
    EXPECT_EQ(out.size(), 0u) << text(message);
  }
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
