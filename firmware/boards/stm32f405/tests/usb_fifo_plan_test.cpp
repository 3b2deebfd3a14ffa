// The OTG FS driver's arithmetic (usb_fifo_plan.hpp): its FIFO RAM plan against RM0090's
// rules, the endpoints it takes from the descriptor parameters, how it cuts IN transfers
// into packets (against the protocol's bulk framing) and how bytes go into FIFO words.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "tetrapulse/stm32f405/usb_fifo_plan.hpp"

namespace tetrapulse::stm32f405 {
namespace {

namespace tp = protocol;

TEST(UsbFifoPlan, FitsTheCoresFifoRam) {
  const FifoPlan p = kFifoPlan;
  EXPECT_TRUE(plan_fits(p));
  EXPECT_LE(size_t{p.bulk_in_start} + p.bulk_in_words, kOtgFifoWords);
  // RM0090 §34.11.3 for one control and two OUT endpoints of 64-byte packets: 35 words.
  EXPECT_EQ(min_rx_fifo_words(64, 2), 35u);
  EXPECT_GE(p.bulk_in_words * 4u, tp::kUsbBulkMaxTransfer) << "a whole answer fits the bulk IN FIFO";
}

TEST(UsbFifoPlan, RefusesOverlapsAndShortFifos) {
  const FifoPlan good = kFifoPlan;
  FifoPlan p = good;
  p.rx_words = 34;  // under the receive FIFO minimum
  p.tx0_start = 34;
  p.bulk_in_start = static_cast<uint16_t>(34 + p.tx0_words);
  EXPECT_FALSE(plan_fits(p));
  p = good;
  p.tx0_start = static_cast<uint16_t>(good.rx_words - 1);  // overlaps the receive FIFO
  EXPECT_FALSE(plan_fits(p));
  p = good;
  p.tx0_words = 15;  // under a packet and the minimum
  p.bulk_in_start = static_cast<uint16_t>(p.tx0_start + 15);
  EXPECT_FALSE(plan_fits(p));
  p = good;
  p.bulk_in_words = static_cast<uint16_t>(words_for(tp::kUsbBulkMaxTransfer) - 1);  // one word short
  EXPECT_FALSE(plan_fits(p));
  p = good;
  p.bulk_in_words = static_cast<uint16_t>(kOtgFifoWords - good.bulk_in_start + 1);  // past the RAM
  EXPECT_FALSE(plan_fits(p));
}

TEST(UsbFifoPlan, BulkEndpointsAreTheDescriptorsAddresses) {
  const tp::Result<BulkEndpoints> defaults = bulk_endpoints(tp::UsbDeviceParams{});
  ASSERT_TRUE(defaults.ok());
  EXPECT_EQ(defaults->out, tp::kUsbBulkOutEndpoint);
  EXPECT_EQ(defaults->in, tp::kUsbBulkInEndpoint & 0x7Fu);

  // Every pair of address bytes: accepted exactly for OUT 0x01..0x03 and IN 0x81..0x83.
  size_t accepted = 0;
  for (unsigned out = 0; out < 256; ++out) {
    for (unsigned in = 0; in < 256; ++in) {
      tp::UsbDeviceParams p;
      p.bulk_out_address = static_cast<uint8_t>(out);
      p.bulk_in_address = static_cast<uint8_t>(in);
      const tp::Result<BulkEndpoints> e = bulk_endpoints(p);
      const bool valid = out >= 0x01 && out <= 0x03 && in >= 0x81 && in <= 0x83;
      ASSERT_EQ(e.ok(), valid) << std::hex << "out 0x" << out << " in 0x" << in;
      if (!e) continue;
      ++accepted;
      EXPECT_EQ(e->out, out);
      EXPECT_EQ(e->in | 0x80u, in);
    }
  }
  EXPECT_EQ(accepted, 9u);
}

TEST(UsbFifoPlan, InTransfersTakeWholePacketsAndWords) {
  for (size_t bytes = 0; bytes <= tp::kUsbBulkMaxTransfer; ++bytes) {
    const InTransfer t = in_transfer(bytes);
    ASSERT_GE(t.packets, 1u);
    EXPECT_GE(t.packets * size_t{tp::kUsbMaxPacketSize}, bytes) << bytes;
    if (bytes != 0) {
      EXPECT_LT((t.packets - 1) * size_t{tp::kUsbMaxPacketSize}, bytes) << bytes;
    }
    EXPECT_GE(t.words * 4u, bytes);
    EXPECT_LT(t.words * 4u, bytes + 4);
    EXPECT_LE(t.words, kFifoPlan.bulk_in_words);
    // On the bus: these packets, and the driver's separate ZLP when the framing needs one.
    if (bytes != 0) {
      const size_t on_bus = t.packets + (tp::usb_bulk_needs_zlp(bytes) ? 1 : 0);
      EXPECT_EQ(on_bus, tp::usb_bulk_packet_count(bytes)) << bytes;
    }
  }
  EXPECT_EQ(in_transfer(0).packets, 1u) << "a zero-length packet is one packet";
  EXPECT_EQ(in_transfer(0).words, 0u);
}

TEST(UsbFifoPlan, FifoWordsAreLittleEndian) {
  const uint8_t bytes[] = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06};
  const tp::ByteView view{bytes, sizeof(bytes)};
  EXPECT_EQ(fifo_word(view, 0), 0x04030201u);
  EXPECT_EQ(fifo_word(view, 1), 0x00000605u) << "the bytes past the end are zero";
}

RC_GTEST_PROP(UsbFifoPlan, PacketsSurviveTheFifoWords, ()) {
  const auto packet = *rc::gen::container<std::vector<uint8_t>>(*rc::gen::inRange<size_t>(0, 65), rc::gen::arbitrary<uint8_t>());
  const auto capacity = *rc::gen::inRange<size_t>(0, 80);
  const tp::ByteView view{packet.data(), packet.size()};
  std::vector<uint8_t> out(80, 0xEE);
  for (size_t i = 0; i < words_for(packet.size()); ++i) {
    store_fifo_word(fifo_word(view, i), i, packet.size(), out.data(), capacity);
  }
  for (size_t i = 0; i < out.size(); ++i) {
    if (i < packet.size() && i < capacity) {
      RC_ASSERT(out[i] == packet[i]);
    } else {
      RC_ASSERT(out[i] == 0xEE);  // nothing written past the packet or the room
    }
  }
}

}  // namespace
}  // namespace tetrapulse::stm32f405
