#include "tetrapulse/protocol/usb_bulk_frame.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <random>
#include <vector>

#include "transport_testing.hpp"

namespace tetrapulse::protocol {
namespace {

using testing::usb_packets;

using Bytes = std::vector<uint8_t>;

Bytes random_message(std::mt19937& rng, size_t size) {
  Bytes m(size);
  for (auto& b : m) b = static_cast<uint8_t>(rng());
  return m;
}

Bytes transfer_of(const Bytes& m) {
  Bytes out(kUsbBulkMaxTransfer);
  const Result<size_t> n = encode_usb_bulk_frame(ByteView{m.data(), m.size()}, out.data(), out.size());
  EXPECT_TRUE(n.ok());
  out.resize(n.ok() ? *n : 0);
  return out;
}

struct Received {
  std::vector<Bytes> messages;
  std::vector<Error> errors;
};

Received push(UsbBulkFrameReceiver& rx, const std::vector<Bytes>& packets) {
  Received out;
  for (const Bytes& p : packets) {
    const ReceiveEvent e = rx.push_packet(ByteView{p.data(), p.size()});
    if (e.kind == ReceiveKind::kMessage) out.messages.emplace_back(e.message.begin(), e.message.end());
    if (e.kind == ReceiveKind::kError) out.errors.push_back(e.error);
  }
  return out;
}

TEST(UsbBulkFrame, PacketBoundaries) {
  EXPECT_EQ(kUsbBulkReadSize, 384u);
  // message size -> transfer size, packets on the bus, ZLP
  struct Case {
    size_t message, transfer, packets;
    bool zlp;
  };
  for (const Case& c : {Case{3, 5, 1, false}, Case{61, 63, 1, false}, Case{62, 64, 2, true},
                        Case{63, 65, 2, false}, Case{126, 128, 3, true}, Case{127, 129, 3, false},
                        Case{254, 256, 5, true}, Case{318, 320, 6, true}, Case{320, 322, 6, false}}) {
    std::mt19937 rng(static_cast<unsigned>(c.message));
    const Bytes m = random_message(rng, c.message);
    const Bytes t = transfer_of(m);
    ASSERT_EQ(t.size(), c.transfer);
    EXPECT_EQ(t[0] | (t[1] << 8), static_cast<int>(c.message));
    EXPECT_EQ(usb_bulk_needs_zlp(t.size()), c.zlp) << c.message;
    const auto packets = usb_packets(t);
    EXPECT_EQ(packets.size(), c.packets) << c.message;
    EXPECT_EQ(usb_bulk_packet_count(t.size()), c.packets) << c.message;
    EXPECT_EQ(packets.back().empty(), c.zlp);
    UsbBulkFrameReceiver rx;
    const Received r = push(rx, packets);
    ASSERT_EQ(r.messages.size(), 1u) << c.message;
    EXPECT_EQ(r.messages[0], m);
    EXPECT_TRUE(r.errors.empty());
  }
}

TEST(UsbBulkFrame, EveryLengthRoundTrips) {
  std::mt19937 rng(1);
  UsbBulkFrameReceiver rx;
  for (size_t size = 3; size <= kMaxMessageSize; ++size) {
    const Bytes m = random_message(rng, size);
    const Bytes t = transfer_of(m);
    const Result<ByteView> whole = decode_usb_bulk_frame(ByteView{t.data(), t.size()});
    ASSERT_TRUE(whole.ok());
    EXPECT_EQ(Bytes(whole->begin(), whole->end()), m);
    const Received r = push(rx, usb_packets(t));
    ASSERT_EQ(r.messages.size(), 1u) << size;
    EXPECT_EQ(r.messages[0], m);
  }
}

RC_GTEST_PROP(UsbBulkFrame, RandomMessagesRoundTrip, ()) {
  const auto size = *rc::gen::inRange<size_t>(3, kMaxMessageSize + 1);
  const auto m = *rc::gen::container<Bytes>(size, rc::gen::arbitrary<uint8_t>());
  UsbBulkFrameReceiver rx;
  const Received r = push(rx, usb_packets(transfer_of(m)));
  RC_ASSERT(r.messages.size() == 1u);
  RC_ASSERT(r.messages[0] == m);
}

TEST(UsbBulkFrame, DecodeChecksTheLengthField) {
  const auto decode = [](Bytes t) { return decode_usb_bulk_frame(ByteView{t.data(), t.size()}).error(); };
  EXPECT_EQ(decode({}), Error::kTruncated);
  EXPECT_EQ(decode({3}), Error::kTruncated);
  EXPECT_EQ(decode({3, 0, 1, 4}), Error::kBadLength);             // says 3, carries 2
  EXPECT_EQ(decode({3, 0, 1, 4, 7, 9}), Error::kBadLength);       // says 3, carries 4
  EXPECT_EQ(decode({2, 0, 1, 4}), Error::kBadLength);             // under 3
  Bytes big(2 + 321, 1);
  big[0] = 321 & 0xFF;
  big[1] = 321 >> 8;
  EXPECT_EQ(decode(big), Error::kBadLength);                      // over kMaxMessageSize
  EXPECT_EQ(decode({3, 0, 1, 4, 7}), Error::kNone);
}

TEST(UsbBulkFrame, EncodeRefusesBadInput) {
  uint8_t out[kUsbBulkMaxTransfer];
  const Bytes two{1, 2}, ok{1, 2, 3}, too_long(321, 1);
  EXPECT_EQ(encode_usb_bulk_frame(ByteView{two.data(), 2}, out, sizeof(out)).error(), Error::kBadLength);
  EXPECT_EQ(encode_usb_bulk_frame(ByteView{too_long.data(), 321}, out, sizeof(out)).error(), Error::kBadLength);
  EXPECT_EQ(encode_usb_bulk_frame(ByteView{ok.data(), 3}, out, 4).error(), Error::kBufferTooSmall);
}

TEST(UsbBulkFrame, MissingZlpCostsTwoTransfersThenResynchronises) {
  std::mt19937 rng(2);
  const Bytes a = random_message(rng, 62), b = random_message(rng, 10), c = random_message(rng, 100);
  auto pa = usb_packets(transfer_of(a));
  ASSERT_TRUE(pa.back().empty());
  pa.pop_back();  // the sender forgot the ZLP: a and b run together
  std::vector<Bytes> stream = pa;
  for (const auto& p : usb_packets(transfer_of(b))) stream.push_back(p);
  for (const auto& p : usb_packets(transfer_of(c))) stream.push_back(p);
  UsbBulkFrameReceiver rx;
  const Received r = push(rx, stream);
  EXPECT_EQ(r.errors, std::vector<Error>{Error::kBadLength});
  ASSERT_EQ(r.messages.size(), 1u);
  EXPECT_EQ(r.messages[0], c);
}

TEST(UsbBulkFrame, OverlongTransferIsReportedOnceAndSkipped) {
  std::mt19937 rng(3);
  std::vector<Bytes> stream(7, Bytes(64, 0xAA));  // 448 bytes with no short packet yet
  stream.push_back(Bytes(10, 0xAA));
  const Bytes m = random_message(rng, 5);
  for (const auto& p : usb_packets(transfer_of(m))) stream.push_back(p);
  UsbBulkFrameReceiver rx;
  const Received r = push(rx, stream);
  EXPECT_EQ(r.errors, std::vector<Error>{Error::kBadLength});
  ASSERT_EQ(r.messages.size(), 1u);
  EXPECT_EQ(r.messages[0], m);
  // A packet over 64 bytes cannot come from a full-speed bulk endpoint.
  const Bytes huge(65, 1);
  EXPECT_EQ(rx.push_packet(ByteView{huge.data(), huge.size()}).error, Error::kBadFraming);
  // A lone ZLP is nothing.
  EXPECT_EQ(rx.push_packet(ByteView{}).kind, ReceiveKind::kNothing);
}

}  // namespace
}  // namespace tetrapulse::protocol
