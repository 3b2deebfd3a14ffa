// Endpoint 0's packet rules (USB 2.0 §8.5.3, §5.5.3) for every answer size and wLength:
// IN data stages carry min(answer, wLength) bytes in full packets and one short packet,
// with a zero-length packet exactly when the data ends early on a packet boundary; OUT
// data stages arrive whole; a SETUP abandons the transfer in progress.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <vector>

#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;
using Action = UsbEndpointZero::Action;

constexpr uint8_t kAnswer = 1;   // vendor IN, wValue = bytes to answer
constexpr uint8_t kTake = 2;     // vendor OUT: the data stage is stored
constexpr uint8_t kRefuse = 3;   // vendor OUT: the data stage is refused

// A function that answers IN requests with a counting pattern and keeps OUT data stages.
class LoopbackFunction final : public UsbFunction {
 public:
  std::vector<uint8_t> taken;
  std::vector<uint8_t> completed;  // bRequest of every status_complete

 private:
  UsbControlReply do_setup(const UsbSetup& s, uint8_t*, size_t) override {
    if (s.request == kAnswer && s.device_to_host()) {
      for (size_t i = 0; i < s.value; ++i) answer_[i] = static_cast<uint8_t>(i * 13 + 5);
      return UsbControlReply::send(answer_, s.value);
    }
    if ((s.request == kTake || s.request == kRefuse) && !s.device_to_host()) {
      return UsbControlReply::receive(in_, sizeof(in_));
    }
    return UsbControlReply::stall();
  }
  bool do_data_out(const UsbSetup& s, tp::ByteView data) override {
    if (s.request == kRefuse) return false;
    taken.assign(data.begin(), data.end());
    return true;
  }
  void do_status_complete(const UsbSetup& s) override { completed.push_back(s.request); }
  void do_bus_reset() override {}

  uint8_t answer_[1024] = {};
  uint8_t in_[1024] = {};
};

struct LoopbackDevice {
  LoopbackDevice() : control(bootloader_params(), "1", controller, buffer, sizeof(buffer)), host(control) {
    control.set_function(0, loopback);
    enumerate(host, controller);
  }
  static tp::UsbDeviceParams bootloader_params() {
    tp::UsbDeviceParams p;
    p.mode = tp::UsbMode::kBootloader;
    return p;
  }
  RecordingController controller;
  uint8_t buffer[64] = {};
  UsbControl control;
  LoopbackFunction loopback;
  PacketHost host;
};

RC_GTEST_PROP(UsbEndpointZero, InDataStageFollowsThePacketRules, ()) {
  LoopbackDevice d;
  const auto answer = *rc::gen::inRange<uint16_t>(0, 1025);
  const auto length = *rc::gen::inRange<uint16_t>(1, 1200);
  UsbSetup s = vendor_in(kAnswer, 0, length);
  s.value = answer;
  const ControlResult r = d.host.in(s);
  RC_ASSERT(!r.stalled);
  const size_t expected = std::min<size_t>(answer, length);
  RC_ASSERT(r.data.size() == expected);
  for (size_t i = 0; i < expected; ++i) RC_ASSERT(r.data[i] == static_cast<uint8_t>(i * 13 + 5));
  const bool zlp = expected < length && expected % 64 == 0;
  const size_t packets = expected / 64 + (expected % 64 != 0 || zlp ? 1 : 0);
  RC_ASSERT(r.packet_sizes.size() == packets);
  for (size_t i = 0; i + 1 < r.packet_sizes.size(); ++i) RC_ASSERT(r.packet_sizes[i] == 64u);
  if (zlp) RC_ASSERT(r.packet_sizes.back() == 0u);
  RC_ASSERT(d.loopback.completed == std::vector<uint8_t>{kAnswer});
}

RC_GTEST_PROP(UsbEndpointZero, OutDataStageArrivesWhole, ()) {
  LoopbackDevice d;
  const auto data = *rc::gen::container<std::vector<uint8_t>>(*rc::gen::inRange<size_t>(0, 1025), rc::gen::arbitrary<uint8_t>());
  UsbSetup s = vendor_out(kTake, 0, static_cast<uint16_t>(data.size()));
  const ControlResult r = d.host.out(s, data);
  RC_ASSERT(!r.stalled);
  RC_ASSERT(d.loopback.taken == data);
  RC_ASSERT(d.loopback.completed == std::vector<uint8_t>{kTake});
}

// A driver that reads its receive FIFO itself (STM32 OTG FS) puts each OUT packet where
// out_target() says and reports its size: the data stage arrives as through on_out_packet.
RC_GTEST_PROP(UsbEndpointZero, OutPacketsPlacedByTheDriverArriveWhole, ()) {
  LoopbackDevice d;
  UsbEndpointZero ep0(d.control);
  const auto data = *rc::gen::container<std::vector<uint8_t>>(*rc::gen::inRange<size_t>(1, 1025), rc::gen::arbitrary<uint8_t>());
  uint8_t setup[kUsbSetupSize];
  encode_usb_setup(vendor_out(kTake, 0, static_cast<uint16_t>(data.size())), setup);
  Action action = ep0.on_setup(setup);
  size_t sent = 0;
  while (action == Action::kReceivePacket) {
    const size_t packet = std::min<size_t>(64, data.size() - sent);
    size_t room = 0;
    uint8_t* into = ep0.out_target(&room);
    RC_ASSERT(room == packet);  // never more than the rest of wLength, never over 64
    std::copy(data.begin() + static_cast<std::ptrdiff_t>(sent), data.begin() + static_cast<std::ptrdiff_t>(sent + packet), into);
    sent += packet;
    action = ep0.on_out_received(packet);
  }
  RC_ASSERT(action == Action::kSendStatus);
  RC_ASSERT(sent == data.size());
  RC_ASSERT(ep0.on_in_complete() == Action::kNone);
  RC_ASSERT(d.loopback.taken == data);
  RC_ASSERT(d.loopback.completed == std::vector<uint8_t>{kTake});
}

TEST(UsbEndpointZero, PlacedPacketLongerThanItsRoomStalls) {
  LoopbackDevice d;
  UsbEndpointZero ep0(d.control);
  uint8_t setup[kUsbSetupSize];
  encode_usb_setup(vendor_out(kTake, 0, 10), setup);
  ASSERT_EQ(ep0.on_setup(setup), Action::kReceivePacket);
  size_t room = 0;
  ep0.out_target(&room);
  ASSERT_EQ(room, 10u);
  EXPECT_EQ(ep0.on_out_received(11), Action::kStall);  // the driver dropped it, reports its size
  EXPECT_TRUE(d.loopback.taken.empty());
  ep0.out_target(&room);
  EXPECT_EQ(room, 0u) << "after the stall only a new SETUP is taken";
}

TEST(UsbEndpointZero, RefusedDataStageStallsTheStatus) {
  LoopbackDevice d;
  EXPECT_TRUE(d.host.out(vendor_out(kRefuse, 0, 5), {1, 2, 3, 4, 5}).stalled);
  EXPECT_TRUE(d.loopback.completed.empty()) << "no status stage after a stall";
}

TEST(UsbEndpointZero, MoreThanWLengthStalls) {
  RecordingController controller;
  uint8_t buffer[64];
  tp::UsbDeviceParams p;
  p.mode = tp::UsbMode::kBootloader;
  UsbControl control(p, "1", controller, buffer, sizeof(buffer));
  LoopbackFunction loopback;
  control.set_function(0, loopback);
  PacketHost host(control);
  enumerate(host, controller);
  UsbEndpointZero ep0(control);
  uint8_t setup[kUsbSetupSize];
  encode_usb_setup(vendor_out(kTake, 0, 10), setup);
  ASSERT_EQ(ep0.on_setup(setup), Action::kReceivePacket);
  const uint8_t packet[64] = {};
  EXPECT_EQ(ep0.on_out_packet(tp::ByteView{packet, 11}), Action::kStall);
  EXPECT_TRUE(loopback.taken.empty());
}

TEST(UsbEndpointZero, ASetupAbandonsTheTransferInProgress) {
  LoopbackDevice d;
  UsbEndpointZero ep0(d.control);
  uint8_t setup[kUsbSetupSize];
  UsbSetup s = vendor_in(kAnswer, 0, 200);
  s.value = 200;
  encode_usb_setup(s, setup);
  ASSERT_EQ(ep0.on_setup(setup), Action::kSendPacket);
  ASSERT_EQ(ep0.on_in_complete(), Action::kSendPacket);  // the host took packet 1 of 4, then gave up
  encode_usb_setup(get_descriptor(tp::kUsbDescriptorDevice, 0, 18), setup);
  ASSERT_EQ(ep0.on_setup(setup), Action::kSendPacket);
  EXPECT_EQ(ep0.in_packet().size, 18u);
  EXPECT_EQ(ep0.on_in_complete(), Action::kReceiveStatus);
  EXPECT_EQ(ep0.on_out_packet(tp::ByteView{}), Action::kNone);
  EXPECT_TRUE(d.loopback.completed.empty()) << "the abandoned request never completed";
}

TEST(UsbEndpointZero, InRequestWithoutDataStageGetsOnlyTheStatus) {
  LoopbackDevice d;
  // wLength 0: no data stage, whatever the answer; the device's IN ZLP is the status stage.
  UsbSetup s = vendor_in(kAnswer, 0, 0);
  s.value = 100;
  const ControlResult r = d.host.in(s);
  EXPECT_FALSE(r.stalled);
  EXPECT_TRUE(r.data.empty());
  EXPECT_EQ(d.loopback.completed, std::vector<uint8_t>{kAnswer});
}

}  // namespace
}  // namespace tetrapulse::fw::testing
