// MESSAGE_OUT and MESSAGE_IN (SPEC.md §5.3): the wLength limits, and the data stage as
// endpoint 0 packets.
#include "tetrapulse/protocol/usb_control.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "transport_testing.hpp"

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes message_of_size(size_t n) {
  Bytes m(n);
  for (size_t i = 0; i < n; ++i) m[i] = static_cast<uint8_t>(i * 37 + 1);
  return m;
}

ReceiveEvent push(UsbMessageOutReceiver& rx, const Bytes& packet) {
  return rx.push_packet(ByteView{packet.data(), packet.size()});
}

TEST(UsbMessageOut, SetupAcceptsExactlyMessageSizes) {
  for (uint32_t w = 0; w <= 0xFFFF; ++w) {
    const bool valid = w >= 3 && w <= kMaxMessageSize;
    EXPECT_EQ(check_usb_message_out(static_cast<uint16_t>(w)).ok(), valid) << w;
    UsbMessageOutReceiver rx;
    EXPECT_EQ(rx.begin(static_cast<uint16_t>(w)).error(), valid ? Error::kNone : Error::kBadLength) << w;
  }
}

TEST(UsbMessageOut, EveryMessageSizeArrivesWhole) {
  UsbMessageOutReceiver rx;
  for (size_t n = 3; n <= kMaxMessageSize; ++n) {
    const Bytes m = message_of_size(n);
    ASSERT_TRUE(rx.begin(static_cast<uint16_t>(n)).ok());
    const auto packets = testing::usb_packets(m, false);
    EXPECT_EQ(packets.size(), (n + kUsbMaxPacketSize - 1) / kUsbMaxPacketSize) << n;
    for (size_t i = 0; i < packets.size(); ++i) {
      const ReceiveEvent e = push(rx, packets[i]);
      if (i + 1 < packets.size()) {
        EXPECT_EQ(e.kind, ReceiveKind::kNothing) << n;
        continue;
      }
      ASSERT_EQ(e.kind, ReceiveKind::kMessage) << n << " " << error_name(e.error);
      EXPECT_EQ(Bytes(e.message.begin(), e.message.end()), m);
    }
  }
}

TEST(UsbMessageOut, DataStageOtherThanWLengthIsRefused) {
  UsbMessageOutReceiver rx;
  // No setup stage first.
  EXPECT_EQ(push(rx, Bytes(8, 1)).error, Error::kBadFraming);
  // A short packet before wLength bytes: the host ended the stage early.
  ASSERT_TRUE(rx.begin(100).ok());
  EXPECT_EQ(push(rx, Bytes(64, 1)).kind, ReceiveKind::kNothing);
  EXPECT_EQ(push(rx, Bytes(35, 1)).error, Error::kTruncated);
  // More bytes than wLength.
  ASSERT_TRUE(rx.begin(10).ok());
  EXPECT_EQ(push(rx, Bytes(11, 1)).error, Error::kBadLength);
  // A packet larger than endpoint 0 takes.
  ASSERT_TRUE(rx.begin(100).ok());
  EXPECT_EQ(push(rx, Bytes(65, 1)).error, Error::kBadFraming);
  // After an error the next setup starts afresh.
  EXPECT_EQ(push(rx, Bytes(3, 1)).error, Error::kBadFraming);
  ASSERT_TRUE(rx.begin(3).ok());
  EXPECT_EQ(push(rx, Bytes{1, 4, 7}).kind, ReceiveKind::kMessage);
  // A refused setup leaves nothing in progress.
  EXPECT_FALSE(rx.begin(2).ok());
  EXPECT_EQ(push(rx, Bytes{1, 4}).error, Error::kBadFraming);
}

TEST(UsbMessageIn, StallsWhenWLengthIsShorterThanThePendingMessage) {
  for (size_t pending = 0; pending <= kMaxMessageSize; ++pending) {
    for (uint16_t w : {uint16_t{0}, uint16_t{3}, uint16_t{64}, uint16_t{200}, uint16_t{kMaxMessageSize}, uint16_t{512}}) {
      EXPECT_EQ(check_usb_message_in(w, pending).ok(), pending <= w) << pending << " " << w;
    }
  }
}

TEST(UsbMessageIn, ZeroLengthPacketOnlyAfterAShortWholePacketStage) {
  EXPECT_TRUE(usb_control_in_needs_zlp(0, kMaxMessageSize));  // nothing pending: one ZLP
  EXPECT_FALSE(usb_control_in_needs_zlp(3, kMaxMessageSize));
  EXPECT_TRUE(usb_control_in_needs_zlp(64, kMaxMessageSize));
  EXPECT_TRUE(usb_control_in_needs_zlp(256, kMaxMessageSize));
  EXPECT_FALSE(usb_control_in_needs_zlp(320, kMaxMessageSize));  // wLength reached ends the stage
  EXPECT_FALSE(usb_control_in_needs_zlp(64, 64));
  EXPECT_FALSE(usb_control_in_needs_zlp(0, 0));
}

}  // namespace
}  // namespace tetrapulse::protocol
