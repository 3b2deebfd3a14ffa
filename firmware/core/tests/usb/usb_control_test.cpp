// The application's USB device through its control endpoint, in 64-byte packets as the
// STM32 driver moves them: enumeration against the golden descriptors (SPEC.md §5.2),
// the standard requests it answers and the ones it stalls, the message interface's
// vendor requests (§5.3) and its bulk framing (§5.4).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_message_function.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_device.hpp"
#include "transport_vectors.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;
using tp::UsbVendorRequest;

constexpr char kSerial[] = "0123456789ABCDEF01234567";

class RecordingPipe final : public UsbPipe {
 public:
  std::vector<std::vector<uint8_t>> transfers;

 private:
  tp::Status do_send_bulk(tp::ByteView t) override {
    transfers.emplace_back(t.begin(), t.end());
    return {};
  }
};

class StepClock final : public LocalClock {
 public:
  Tick t = 1000;

 private:
  Tick do_now() const override { return t; }
  uint32_t do_tick_hz() const override { return 1'000'000; }
};

// Answers every message with an Ack of its type and seq on the path it came by, as the
// firmware does; remembers what arrived and how.
class AckingSink final : public MessageSink {
 public:
  std::vector<std::vector<uint8_t>> received;
  std::vector<uint8_t> paths;
  std::vector<Tick> ticks;

 private:
  void do_on_message(const ReceivedMessage& m) override {
    received.emplace_back(m.bytes.begin(), m.bytes.end());
    paths.push_back(m.reply.peer);
    ticks.push_back(m.rx_tick);
    uint8_t out[16];
    tp::ByteWriter w(out, sizeof(out));
    const auto type = static_cast<tp::MessageType>(m.bytes[1]);
    if (!tp::encode(tp::Message{m.bytes[2], tp::Ack{type, 7}}, w)) return;
    m.link->send(m.reply, w.view());
  }
};

class NoDetach final : public DfuRuntimeTarget {
  void do_detach() override {}
};

struct AppDevice {
  explicit AppDevice(const tp::UsbDeviceParams& p = tp::UsbDeviceParams{})
      : params(p), control(params, kSerial, controller, buffer, sizeof(buffer)), dfu(detach, params) {
    control.set_function(0, messages);
    control.set_function(1, dfu);
  }
  tp::UsbDeviceParams params;
  RecordingController controller;
  RecordingPipe pipe;
  UsbLink link{pipe};
  AckingSink sink;
  StepClock clock;
  uint8_t buffer[tp::kMaxMessageSize] = {};
  UsbControl control;
  UsbMessageFunction messages{link, sink, clock,
                              tp::kUsbCapabilityBulkMessages | tp::kUsbCapabilityControlMessages |
                                  tp::kUsbCapabilityDfuRuntime};
  NoDetach detach;
  DfuDevice dfu;
  PacketHost host{control};
};

std::vector<uint8_t> message_out(AppDevice& d, const std::vector<uint8_t>& m, bool* stalled = nullptr) {
  const ControlResult r = d.host.out(
      vendor_out(static_cast<uint8_t>(UsbVendorRequest::kMessageOut), 0, static_cast<uint16_t>(m.size())), m);
  if (stalled != nullptr) *stalled = r.stalled;
  return r.data;
}

ControlResult message_in(AppDevice& d, uint16_t length = tp::kMaxMessageSize) {
  return d.host.in(vendor_in(static_cast<uint8_t>(UsbVendorRequest::kMessageIn), 0, length));
}

std::vector<uint8_t> ack_bytes(uint8_t seq, tp::MessageType type) {
  uint8_t out[16];
  tp::ByteWriter w(out, sizeof(out));
  EXPECT_TRUE(tp::encode(tp::Message{seq, tp::Ack{type, 7}}, w).ok());
  return std::vector<uint8_t>(out, out + w.size());
}

TEST(UsbControl, EnumeratesWithTheGoldenDescriptorsOfBothModes) {
  const auto files = tp::testing::read_vectors("usb", "descriptors_");
  ASSERT_TRUE(files.has_value()) << files.error();
  size_t modes = 0;
  for (const tp::testing::HexFile& f : *files) {
    if (f.stem != "descriptors_application" && f.stem != "descriptors_bootloader") continue;
    ++modes;
    const auto v = tp::testing::usb_descriptor_vector(f);
    ASSERT_TRUE(v.has_value()) << v.error();
    RecordingController controller;
    uint8_t buffer[tp::kMaxMessageSize];
    UsbControl control(v->params, kSerial, controller, buffer, sizeof(buffer));
    PacketHost host(control);
    EXPECT_EQ(host.in(get_descriptor(tp::kUsbDescriptorDevice, 0, 64)).data, v->device) << f.path;
    const std::vector<uint8_t> config = enumerate(host, controller);
    EXPECT_EQ(config, v->configuration) << f.path;
    EXPECT_TRUE(control.configured());
  }
  EXPECT_EQ(modes, 2u);
}

TEST(UsbControl, StringsAreTheSpecsAndTheSerial) {
  AppDevice d;
  const ControlResult languages = d.host.in(get_descriptor(tp::kUsbDescriptorString, 0, 255));
  EXPECT_EQ(languages.data, (std::vector<uint8_t>{0x04, 0x03, 0x09, 0x04}));
  EXPECT_EQ(string_of(d.host.in(get_descriptor(tp::kUsbDescriptorString, 1, 255, 0x0409)).data), "tetrapulse");
  EXPECT_EQ(string_of(d.host.in(get_descriptor(tp::kUsbDescriptorString, 2, 255, 0x0409)).data), "tetrapulse");
  const ControlResult serial = d.host.in(get_descriptor(tp::kUsbDescriptorString, 3, 255, 0x0409));
  EXPECT_EQ(string_of(serial.data), kSerial);
  EXPECT_EQ(serial.data[0], 2 + 2 * 24);
  EXPECT_EQ(string_of(d.host.in(get_descriptor(tp::kUsbDescriptorString, 4, 255, 0x0409)).data),
            "tetrapulse firmware");
  EXPECT_TRUE(d.host.in(get_descriptor(tp::kUsbDescriptorString, 5, 255, 0x0409)).stalled);
}

TEST(UsbControl, ShortReadsGetTheFirstBytesAndNoMore) {
  AppDevice d;
  const ControlResult eight = d.host.in(get_descriptor(tp::kUsbDescriptorDevice, 0, 8));
  EXPECT_EQ(eight.data.size(), 8u);
  EXPECT_EQ(eight.data[7], 64) << "bMaxPacketSize0";
  const ControlResult config = d.host.in(get_descriptor(tp::kUsbDescriptorConfiguration, 0, 255));
  EXPECT_EQ(config.data.size(), 50u);
  EXPECT_EQ(config.packet_sizes, (std::vector<size_t>{50}));
}

TEST(UsbControl, StallsWhatAFullSpeedDeviceDoesNotHave) {
  AppDevice d;
  enumerate(d.host, d.controller);
  const auto stalls = [&](const UsbSetup& s) { return d.host.in(s).stalled; };
  EXPECT_TRUE(stalls(get_descriptor(6, 0, 10))) << "device qualifier";
  EXPECT_TRUE(stalls(get_descriptor(7, 0, 255))) << "other speed configuration";
  EXPECT_TRUE(stalls(get_descriptor(15, 0, 5))) << "BOS";
  EXPECT_TRUE(stalls(get_descriptor(tp::kUsbDescriptorConfiguration, 1, 255))) << "a second configuration";
  const auto out_stalls = [&](const UsbSetup& s) { return d.host.out(s, {}).stalled; };
  EXPECT_TRUE(out_stalls(standard_out(UsbRecipient::kDevice, usb_request::kSetFeature, kUsbFeatureRemoteWakeup, 0)));
  EXPECT_TRUE(out_stalls(standard_out(UsbRecipient::kDevice, usb_request::kSetConfiguration, 2, 0)));
  EXPECT_TRUE(out_stalls(standard_out(UsbRecipient::kInterface, usb_request::kSetInterface, 1, 0)));
  EXPECT_TRUE(out_stalls(standard_out(UsbRecipient::kInterface, usb_request::kSetInterface, 0, 2)));
  EXPECT_TRUE(out_stalls(standard_out(UsbRecipient::kDevice, usb_request::kSetAddress, 5, 0)))
      << "SET_ADDRESS in the configured state";
  EXPECT_TRUE(stalls(vendor_in(0x77, 0, 8))) << "unknown vendor request";
  EXPECT_TRUE(stalls(vendor_in(static_cast<uint8_t>(UsbVendorRequest::kProtocolInfo), 2, 8))) << "no interface 2";
  // The device answers on after every stall.
  EXPECT_FALSE(stalls(get_descriptor(tp::kUsbDescriptorDevice, 0, 18)));
}

TEST(UsbControl, InterfaceRequestsWaitForTheConfiguration) {
  AppDevice d;
  const UsbSetup info = vendor_in(static_cast<uint8_t>(UsbVendorRequest::kProtocolInfo), 0, 8);
  EXPECT_TRUE(d.host.in(info).stalled);
  enumerate(d.host, d.controller);
  EXPECT_FALSE(d.host.in(info).stalled);
  EXPECT_FALSE(d.host.out(standard_out(UsbRecipient::kDevice, usb_request::kSetConfiguration, 0, 0), {}).stalled);
  EXPECT_FALSE(d.controller.configured);
  EXPECT_TRUE(d.host.in(info).stalled);
  d.host.bus_reset();
  EXPECT_FALSE(d.control.configured());
}

TEST(UsbControl, StatusConfigurationAndInterfaceQueries) {
  tp::UsbDeviceParams p;
  p.self_powered = true;
  AppDevice d(p);
  const UsbSetup get_config = standard_in(UsbRecipient::kDevice, usb_request::kGetConfiguration, 0, 0, 1);
  EXPECT_EQ(d.host.in(get_config).data, (std::vector<uint8_t>{0}));
  enumerate(d.host, d.controller);
  EXPECT_EQ(d.host.in(get_config).data, (std::vector<uint8_t>{1}));
  EXPECT_EQ(d.host.in(standard_in(UsbRecipient::kDevice, usb_request::kGetStatus, 0, 0, 2)).data,
            (std::vector<uint8_t>{1, 0}))
      << "self powered, no remote wakeup";
  EXPECT_EQ(d.host.in(standard_in(UsbRecipient::kInterface, usb_request::kGetStatus, 0, 1, 2)).data,
            (std::vector<uint8_t>{0, 0}));
  EXPECT_EQ(d.host.in(standard_in(UsbRecipient::kInterface, usb_request::kGetInterface, 0, 1, 1)).data,
            (std::vector<uint8_t>{0}));
  EXPECT_FALSE(d.host.out(standard_out(UsbRecipient::kInterface, usb_request::kSetInterface, 0, 1), {}).stalled)
      << "dfu-util selects alternate setting 0";
}

TEST(UsbControl, EndpointHaltReachesTheController) {
  AppDevice d;
  enumerate(d.host, d.controller);
  const auto ep_status = [&](uint16_t ep) {
    return d.host.in(standard_in(UsbRecipient::kEndpoint, usb_request::kGetStatus, 0, ep, 2));
  };
  const auto feature = [&](uint8_t request, uint16_t ep) {
    return d.host.out(standard_out(UsbRecipient::kEndpoint, request, kUsbFeatureEndpointHalt, ep), {});
  };
  EXPECT_EQ(ep_status(0x81).data, (std::vector<uint8_t>{0, 0}));
  EXPECT_FALSE(feature(usb_request::kSetFeature, 0x81).stalled);
  EXPECT_EQ(ep_status(0x81).data, (std::vector<uint8_t>{1, 0}));
  EXPECT_EQ(ep_status(0x01).data, (std::vector<uint8_t>{0, 0})) << "only IN halted";
  EXPECT_FALSE(feature(usb_request::kClearFeature, 0x81).stalled);
  EXPECT_EQ(ep_status(0x81).data, (std::vector<uint8_t>{0, 0}));
  EXPECT_FALSE(feature(usb_request::kClearFeature, 0x01).stalled);  // libusb_clear_halt on an idle endpoint
  EXPECT_EQ(d.controller.halts, (std::vector<std::pair<uint8_t, bool>>{{0x81, true}, {0x81, false}, {0x01, false}}));
  EXPECT_TRUE(feature(usb_request::kSetFeature, 0x82).stalled) << "no such endpoint";
  EXPECT_EQ(ep_status(0x00).data, (std::vector<uint8_t>{0, 0}));
}

TEST(UsbMessageFunction, ProtocolInfoIsTheSpecExample) {
  AppDevice d;
  enumerate(d.host, d.controller);
  const uint8_t request = static_cast<uint8_t>(UsbVendorRequest::kProtocolInfo);
  EXPECT_EQ(d.host.in(vendor_in(request, 0, 8)).data, (std::vector<uint8_t>{0x01, 0x00, 0x40, 0x01, 0x07, 0, 0, 0}));
  EXPECT_EQ(d.host.in(vendor_in(request, 0, 64)).data.size(), 8u) << "a longer wLength gets the 8 bytes";
  EXPECT_TRUE(d.host.in(vendor_in(request, 0, 7)).stalled);
}

TEST(UsbMessageFunction, AnswersOfMessageOutComeBackThroughMessageIn) {
  AppDevice d;
  enumerate(d.host, d.controller);
  d.clock.t = 4242;
  bool stalled = true;
  message_out(d, {0x01, 0x04, 0x07}, &stalled);  // GetStatus, seq 7
  EXPECT_FALSE(stalled);
  ASSERT_EQ(d.sink.received.size(), 1u);
  EXPECT_EQ(d.sink.received[0], (std::vector<uint8_t>{0x01, 0x04, 0x07}));
  EXPECT_EQ(d.sink.paths[0], kUsbControlPath);
  EXPECT_EQ(d.sink.ticks[0], 4242u);
  EXPECT_TRUE(d.pipe.transfers.empty()) << "a control-path answer never goes to bulk IN";
  const ControlResult answer = message_in(d);
  EXPECT_EQ(answer.data, ack_bytes(7, tp::MessageType::kGetStatus));
  const ControlResult none = message_in(d);
  EXPECT_FALSE(none.stalled);
  EXPECT_TRUE(none.data.empty());
  EXPECT_EQ(none.packet_sizes, (std::vector<size_t>{0})) << "nothing pending: a zero-length data stage";
}

TEST(UsbMessageFunction, MessageInShorterThanTheAnswerStallsAndKeepsIt) {
  AppDevice d;
  enumerate(d.host, d.controller);
  message_out(d, {0x01, 0x01, 0x09});
  EXPECT_TRUE(message_in(d, 4).stalled);
  EXPECT_EQ(message_in(d).data, ack_bytes(9, tp::MessageType::kGetInfo));
}

TEST(UsbMessageFunction, MessageOutRefusesBadLengthsAndAFullQueue) {
  AppDevice d;
  enumerate(d.host, d.controller);
  bool stalled = false;
  message_out(d, {0x01, 0x04}, &stalled);
  EXPECT_TRUE(stalled) << "2 bytes";
  message_out(d, std::vector<uint8_t>(tp::kMaxMessageSize + 1, 0x11), &stalled);
  EXPECT_TRUE(stalled) << "321 bytes";
  for (uint8_t seq = 0; seq < UsbLink::kControlQueue; ++seq) {
    message_out(d, {0x01, 0x04, seq}, &stalled);
    EXPECT_FALSE(stalled);
  }
  message_out(d, {0x01, 0x04, 99}, &stalled);
  EXPECT_TRUE(stalled) << "no room for the answer";
  EXPECT_EQ(d.sink.received.size(), UsbLink::kControlQueue);
  EXPECT_EQ(message_in(d).data, ack_bytes(0, tp::MessageType::kGetStatus));
  message_out(d, {0x01, 0x04, 99}, &stalled);
  EXPECT_FALSE(stalled) << "room again";
}

TEST(UsbMessageFunction, LongestMessageIsFiveFullPackets) {
  AppDevice d;
  enumerate(d.host, d.controller);
  std::vector<uint8_t> m(tp::kMaxMessageSize);
  for (size_t i = 0; i < m.size(); ++i) m[i] = static_cast<uint8_t>(i * 7 + 1);
  m[1] = 0x11;  // UpdateChunk's type
  const ControlResult r = d.host.out(
      vendor_out(static_cast<uint8_t>(UsbVendorRequest::kMessageOut), 0, static_cast<uint16_t>(m.size())), m);
  EXPECT_FALSE(r.stalled);
  EXPECT_EQ(r.packet_sizes, (std::vector<size_t>{64, 64, 64, 64, 64}));
  ASSERT_EQ(d.sink.received.size(), 1u);
  EXPECT_EQ(d.sink.received[0], m);
}

TEST(UsbMessageFunction, BulkPacketsMakeMessagesAnsweredOnBulkIn) {
  AppDevice d;
  enumerate(d.host, d.controller);
  for (size_t size : {3u, 62u, 126u, 320u}) {
    std::vector<uint8_t> m(size, 0x5A);
    m[0] = 0x01;
    m[1] = 0x04;
    m[2] = static_cast<uint8_t>(size);
    std::vector<uint8_t> transfer(tp::kUsbBulkMaxTransfer);
    const tp::Result<size_t> n = tp::encode_usb_bulk_frame(tp::ByteView{m.data(), m.size()}, transfer.data(),
                                                            transfer.size());
    ASSERT_TRUE(n.ok());
    transfer.resize(*n);
    for (size_t off = 0; off < transfer.size(); off += 64) {
      d.messages.on_bulk_packet(tp::ByteView{transfer.data() + off, std::min<size_t>(64, transfer.size() - off)});
    }
    if (tp::usb_bulk_needs_zlp(transfer.size())) d.messages.on_bulk_packet(tp::ByteView{});
    ASSERT_FALSE(d.sink.received.empty());
    EXPECT_EQ(d.sink.received.back(), m) << size;
    EXPECT_EQ(d.sink.paths.back(), kUsbBulkPath);
    ASSERT_FALSE(d.pipe.transfers.empty());
    const std::vector<uint8_t>& answer = d.pipe.transfers.back();
    const tp::Result<tp::ByteView> decoded = tp::decode_usb_bulk_frame(tp::ByteView{answer.data(), answer.size()});
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::vector<uint8_t>(decoded->begin(), decoded->end()),
              ack_bytes(static_cast<uint8_t>(size), tp::MessageType::kGetStatus));
  }
  EXPECT_EQ(d.sink.received.size(), 4u);
  EXPECT_EQ(d.link.transport_errors(), 0u);
}

}  // namespace
}  // namespace tetrapulse::fw::testing
