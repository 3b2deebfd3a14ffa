#include "tetrapulse/protocol/uart_frame.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <random>
#include <vector>

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes random_message(std::mt19937& rng, size_t size) {
  Bytes m(size);
  for (auto& b : m) b = static_cast<uint8_t>(rng() % 3 == 0 ? 0 : rng());  // plenty of zeros
  m[0] = kProtocolVersion;
  return m;
}

Bytes frame_of(const Bytes& m) {
  Bytes out(uart_max_frame_size(m.size()));
  const Result<size_t> n = encode_uart_frame(ByteView{m.data(), m.size()}, out.data(), out.size());
  EXPECT_TRUE(n.ok()) << error_name(n.error());
  out.resize(n.ok() ? *n : 0);
  return out;
}

struct Decoded {
  std::vector<Bytes> messages;
  std::vector<Error> errors;
};

// Feeds `stream` in pieces of the given sizes (cycled), collecting every event.
Decoded decode(UartFrameDecoder& decoder, const Bytes& stream, const std::vector<size_t>& pieces = {1 << 20}) {
  Decoded out;
  size_t pos = 0, k = 0;
  while (pos < stream.size()) {
    const size_t n = std::min(pieces[k++ % pieces.size()], stream.size() - pos);
    size_t done = 0;
    while (done < n) {
      size_t used = 0;
      const ReceiveEvent e = decoder.feed(ByteView{stream.data() + pos + done, n - done}, &used);
      done += used;
      if (e.kind == ReceiveKind::kMessage) out.messages.emplace_back(e.message.begin(), e.message.end());
      if (e.kind == ReceiveKind::kError) out.errors.push_back(e.error);
    }
    pos += n;
  }
  return out;
}

Decoded decode(const Bytes& stream, const std::vector<size_t>& pieces = {1 << 20}) {
  UartFrameDecoder decoder;
  return decode(decoder, stream, pieces);
}

TEST(UartFrame, LayoutIsCobsOfMessageAndLittleEndianCrcThenZero) {
  const Bytes m{0x01, 0x04, 0x07};
  const uint16_t crc = crc16_ccitt(m.data(), m.size());
  const Bytes f = frame_of(m);
  ASSERT_EQ(f.size(), 3 + 2 + 1 + 1u);
  EXPECT_EQ(f.back(), 0x00);
  Bytes plain(8);
  const Result<size_t> n = cobs_decode(ByteView{f.data(), f.size() - 1}, plain.data(), plain.size());
  ASSERT_TRUE(n.ok());
  plain.resize(*n);
  EXPECT_EQ(plain, (Bytes{0x01, 0x04, 0x07, static_cast<uint8_t>(crc), static_cast<uint8_t>(crc >> 8)}));
}

TEST(UartFrame, EveryLengthRoundTripsAndFitsTheWorstCase) {
  std::mt19937 rng(1);
  EXPECT_EQ(kUartMaxFrameSize, 325u);
  for (size_t size = 3; size <= kMaxMessageSize; ++size) {
    const Bytes m = random_message(rng, size);
    const Bytes f = frame_of(m);
    EXPECT_LE(f.size(), uart_max_frame_size(size));
    for (size_t i = 0; i + 1 < f.size(); ++i) ASSERT_NE(f[i], 0) << "zero inside the frame";
    const Decoded d = decode(f);
    ASSERT_EQ(d.messages.size(), 1u) << size;
    EXPECT_EQ(d.messages[0], m);
    EXPECT_TRUE(d.errors.empty());
  }
  // A message with no zero bytes reaches the worst case exactly... unless its CRC has one.
  Bytes m(kMaxMessageSize, 0x5A);
  for (uint8_t fill = 1; fill != 0; ++fill) {
    m.assign(kMaxMessageSize, fill);
    const uint16_t crc = crc16_ccitt(m.data(), m.size());
    if ((crc & 0xFF) != 0 && (crc >> 8) != 0) break;
  }
  EXPECT_EQ(frame_of(m).size(), kUartMaxFrameSize);
}

RC_GTEST_PROP(UartFrame, RandomMessagesRoundTripInRandomPieces, ()) {
  const auto size = *rc::gen::inRange<size_t>(3, kMaxMessageSize + 1);
  const auto m = *rc::gen::container<Bytes>(size, rc::gen::arbitrary<uint8_t>());
  const auto piece = *rc::gen::inRange<size_t>(1, 400);
  const Decoded d = decode(frame_of(m), {piece});
  RC_ASSERT(d.messages.size() == 1u);
  RC_ASSERT(d.messages[0] == m);
}

TEST(UartFrame, RejectsBadMessagesAndShortBuffers) {
  uint8_t out[kUartMaxFrameSize];
  const Bytes two{1, 2}, too_long(kMaxMessageSize + 1, 1), ok{1, 2, 3};
  EXPECT_EQ(encode_uart_frame(ByteView{two.data(), 2}, out, sizeof(out)).error(), Error::kBadLength);
  EXPECT_EQ(encode_uart_frame(ByteView{too_long.data(), too_long.size()}, out, sizeof(out)).error(),
            Error::kBadLength);
  for (size_t cap = 0; cap < frame_of(ok).size(); ++cap) {
    EXPECT_EQ(encode_uart_frame(ByteView{ok.data(), 3}, out, cap).error(), Error::kBufferTooSmall) << cap;
  }
}

TEST(UartFrame, SplitAtEveryByteGivesTheSameMessages) {
  std::mt19937 rng(2);
  Bytes stream;
  std::vector<Bytes> sent;
  for (size_t size : {3u, 60u, 254u, 300u, 320u}) {
    sent.push_back(random_message(rng, size));
    const Bytes f = frame_of(sent.back());
    stream.insert(stream.end(), f.begin(), f.end());
  }
  for (size_t cut = 0; cut <= stream.size(); ++cut) {
    const Decoded d = decode(stream, {cut == 0 ? stream.size() : cut, stream.size()});
    ASSERT_EQ(d.messages, sent) << "cut " << cut;
    EXPECT_TRUE(d.errors.empty());
  }
  const Decoded bytewise = decode(stream, {1});
  EXPECT_EQ(bytewise.messages, sent);
}

TEST(UartFrame, GarbageBetweenFramesCostsNoFrame) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    Bytes stream;
    std::vector<Bytes> sent;
    for (int k = 0; k < 5; ++k) {
      // Line noise, ended by a delimiter (a sender flushes with 0x00 after idle).
      const size_t noise = rng() % 40;
      for (size_t i = 0; i < noise; ++i) stream.push_back(static_cast<uint8_t>(rng()));
      stream.push_back(0x00);
      sent.push_back(random_message(rng, 3 + rng() % 318));
      const Bytes f = frame_of(sent.back());
      stream.insert(stream.end(), f.begin(), f.end());
    }
    const Decoded d = decode(stream, {1 + rng() % 64});
    // Every frame arrives; noise gives errors, or rarely a noise "message" with a matching CRC.
    size_t next = 0;
    for (const Bytes& m : d.messages) {
      if (next < sent.size() && m == sent[next]) ++next;
    }
    EXPECT_EQ(next, sent.size()) << "trial " << trial;
  }
}

TEST(UartFrame, CorruptedFrameIsReportedAndTheNextOneSurvives) {
  std::mt19937 rng(4);
  for (size_t size : {3u, 20u, 254u, 320u}) {
    const Bytes a = random_message(rng, size), b = random_message(rng, size);
    const Bytes fa = frame_of(a), fb = frame_of(b);
    for (size_t i = 0; i + 1 < fa.size(); ++i) {
      Bytes stream = fa;
      stream[i] ^= static_cast<uint8_t>(1 + rng() % 255);
      stream.insert(stream.end(), fb.begin(), fb.end());
      const Decoded d = decode(stream);
      ASSERT_FALSE(d.messages.empty()) << "size " << size << " byte " << i;
      EXPECT_EQ(d.messages.back(), b);
      EXPECT_FALSE(d.errors.empty()) << "size " << size << " byte " << i;
    }
  }
}

TEST(UartFrame, ErrorsAreTyped) {
  const Bytes m{1, 4, 7};
  Bytes f = frame_of(m);
  // COBS block cut short by the delimiter.
  Decoded d = decode(Bytes{0x05, 0x11, 0x22, 0x00});
  EXPECT_EQ(d.errors, std::vector<Error>{Error::kBadFraming});
  // Four decoded bytes: too short for a message and its CRC.
  d = decode(Bytes{0x05, 0x01, 0x04, 0x07, 0x09, 0x00});
  EXPECT_EQ(d.errors, std::vector<Error>{Error::kBadLength});
  // CRC wrong.
  Bytes bad = f;
  bad[2] ^= 0x40;
  d = decode(bad);
  EXPECT_EQ(d.errors, std::vector<Error>{Error::kBadCrc});
  // Overlong: reported once, as soon as it overflows; the next frame decodes.
  Bytes longer(600, 0x11);
  longer.push_back(0x00);
  longer.insert(longer.end(), f.begin(), f.end());
  d = decode(longer);
  EXPECT_EQ(d.errors, std::vector<Error>{Error::kBadLength});
  ASSERT_EQ(d.messages.size(), 1u);
  EXPECT_EQ(d.messages[0], m);
  // Repeated delimiters are idle line, not errors.
  d = decode(Bytes{0x00, 0x00, 0x00});
  EXPECT_TRUE(d.errors.empty());
  EXPECT_TRUE(d.messages.empty());
}

TEST(UartFrame, OverflowIsDetectedAtTheFirstByteTooMany) {
  // Two full COBS blocks (code 0xFF, 254 data bytes each, no implied zeros): 322
  // decoded bytes fit (a 320-byte message and its CRC), the 323rd does not.
  UartFrameDecoder decoder;
  size_t data = 0, events = 0, error_at = 0;
  for (int block = 0; block < 2; ++block) {
    EXPECT_EQ(decoder.push(0xFF).kind, ReceiveKind::kNothing);
    for (int i = 0; i < 254; ++i) {
      const ReceiveEvent e = decoder.push(0x11);
      ++data;
      if (e.kind == ReceiveKind::kError) {
        ++events;
        error_at = data;
        EXPECT_EQ(e.error, Error::kBadLength);
      }
    }
  }
  EXPECT_EQ(events, 1u);
  EXPECT_EQ(error_at, kMaxMessageSize + kUartCrcSize + 1);
  // The delimiter ends the skipped frame silently.
  EXPECT_EQ(decoder.push(0x00).kind, ReceiveKind::kNothing);
}

}  // namespace
}  // namespace tetrapulse::protocol
