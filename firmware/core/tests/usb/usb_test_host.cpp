#include "usb_test_host.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::fw::testing {

namespace tp = protocol;
using Action = UsbEndpointZero::Action;

namespace {

constexpr size_t kPacket = tp::kUsbMaxPacketSize;

uint8_t request_type(bool in, UsbRequestType type, UsbRecipient to) {
  return static_cast<uint8_t>((in ? 0x80 : 0) | static_cast<uint8_t>(type) << 5 | static_cast<uint8_t>(to));
}

}  // namespace

ControlResult PacketHost::in(const UsbSetup& setup) {
  ControlResult r;
  uint8_t packet[kUsbSetupSize];
  encode_usb_setup(setup, packet);
  Action a = ep0_.on_setup(packet);
  if (a == Action::kStall) {
    r.stalled = true;
    return r;
  }
  if (setup.length == 0) {
    // A device-to-host request without a data stage: the device sends the status ZLP.
    EXPECT_EQ(a, Action::kSendStatus);
    EXPECT_EQ(ep0_.on_in_complete(), Action::kNone);
    return r;
  }
  for (;;) {
    if (a == Action::kStall) {
      r.stalled = true;
      return r;
    }
    if (a != Action::kSendPacket) {
      ADD_FAILURE() << "IN data stage: expected a data packet, got action " << int(a);
      r.stalled = true;
      return r;
    }
    const tp::ByteView p = ep0_.in_packet();
    EXPECT_LE(p.size, kPacket);
    r.data.insert(r.data.end(), p.begin(), p.end());
    r.packet_sizes.push_back(p.size);
    EXPECT_LE(r.data.size(), setup.length) << "more than wLength";
    const bool host_done = p.size < kPacket || r.data.size() >= setup.length;
    a = ep0_.on_in_complete();
    if (host_done) break;
  }
  EXPECT_EQ(a, Action::kReceiveStatus) << "the data stage went on after a short packet or wLength";
  EXPECT_EQ(ep0_.on_out_packet(tp::ByteView{}), Action::kNone);
  return r;
}

ControlResult PacketHost::out(const UsbSetup& setup, const std::vector<uint8_t>& data) {
  ControlResult r;
  uint8_t packet[kUsbSetupSize];
  encode_usb_setup(setup, packet);
  Action a = ep0_.on_setup(packet);
  size_t sent = 0;
  while (a == Action::kReceivePacket) {
    const size_t n = std::min(kPacket, data.size() - sent);
    a = ep0_.on_out_packet(tp::ByteView{data.data() + sent, n});
    sent += n;
    r.packet_sizes.push_back(n);
    if (n < kPacket) break;  // a short packet ends the data stage whatever the device says
    if (sent == data.size() && a == Action::kReceivePacket) {
      a = ep0_.on_out_packet(tp::ByteView{});  // the host ends a full-packet stage early with a ZLP
      r.packet_sizes.push_back(0);
      break;
    }
  }
  if (a == Action::kStall) {
    r.stalled = true;
    return r;
  }
  EXPECT_EQ(a, Action::kSendStatus);
  EXPECT_EQ(ep0_.on_in_complete(), Action::kNone);
  return r;
}

void PacketHost::bus_reset() {
  ep0_.reset();
  control_.bus_reset();
}

ControlResult FunctionHost::in(const UsbSetup& setup) {
  ControlResult r;
  const UsbControlReply reply = function_.setup(setup, scratch_.data(), scratch_.size());
  switch (reply.kind) {
    case UsbControlReply::Kind::kSend: {
      const size_t n = std::min<size_t>(reply.size, setup.length);
      r.data.assign(reply.data, reply.data + n);
      function_.status_complete(setup);
      return r;
    }
    case UsbControlReply::Kind::kAccept:
      EXPECT_EQ(setup.length, 0) << "an IN request accepted without data";
      function_.status_complete(setup);
      return r;
    case UsbControlReply::Kind::kStall:
      r.stalled = true;
      return r;
    case UsbControlReply::Kind::kReceive:
      break;
  }
  ADD_FAILURE() << "IN request answered with receive";
  r.stalled = true;
  return r;
}

ControlResult FunctionHost::out(const UsbSetup& setup, const std::vector<uint8_t>& data) {
  ControlResult r;
  const UsbControlReply reply = function_.setup(setup, scratch_.data(), scratch_.size());
  switch (reply.kind) {
    case UsbControlReply::Kind::kReceive:
      if (reply.size < setup.length) {
        ADD_FAILURE() << "receive buffer smaller than wLength";
        r.stalled = true;
        return r;
      }
      std::copy(data.begin(), data.end(), reply.buffer);
      if (!function_.data_out(setup, tp::ByteView{reply.buffer, data.size()})) {
        r.stalled = true;
        return r;
      }
      function_.status_complete(setup);
      return r;
    case UsbControlReply::Kind::kAccept:
      EXPECT_EQ(setup.length, 0) << "an OUT request with data accepted without receiving it";
      function_.status_complete(setup);
      return r;
    case UsbControlReply::Kind::kStall:
      r.stalled = true;
      return r;
    case UsbControlReply::Kind::kSend:
      break;
  }
  ADD_FAILURE() << "OUT request answered with send";
  r.stalled = true;
  return r;
}

UsbSetup standard_in(UsbRecipient to, uint8_t request, uint16_t value, uint16_t index, uint16_t length) {
  return UsbSetup{request_type(true, UsbRequestType::kStandard, to), request, value, index, length};
}
UsbSetup standard_out(UsbRecipient to, uint8_t request, uint16_t value, uint16_t index) {
  return UsbSetup{request_type(false, UsbRequestType::kStandard, to), request, value, index, 0};
}
UsbSetup get_descriptor(uint8_t type, uint8_t index, uint16_t length, uint16_t language) {
  return standard_in(UsbRecipient::kDevice, usb_request::kGetDescriptor, static_cast<uint16_t>(type << 8 | index),
                     language, length);
}
UsbSetup class_in(uint8_t request, uint16_t value, uint16_t interface, uint16_t length) {
  return UsbSetup{request_type(true, UsbRequestType::kClass, UsbRecipient::kInterface), request, value, interface,
                  length};
}
UsbSetup class_out(uint8_t request, uint16_t value, uint16_t interface, uint16_t length) {
  return UsbSetup{request_type(false, UsbRequestType::kClass, UsbRecipient::kInterface), request, value, interface,
                  length};
}
UsbSetup vendor_in(uint8_t request, uint16_t interface, uint16_t length) {
  return UsbSetup{request_type(true, UsbRequestType::kVendor, UsbRecipient::kInterface), request, 0, interface, length};
}
UsbSetup vendor_out(uint8_t request, uint16_t interface, uint16_t length) {
  return UsbSetup{request_type(false, UsbRequestType::kVendor, UsbRecipient::kInterface), request, 0, interface,
                  length};
}

std::vector<uint8_t> enumerate(ControlPipe& host, RecordingController& controller) {
  const ControlResult first = host.in(get_descriptor(tp::kUsbDescriptorDevice, 0, 64));
  EXPECT_FALSE(first.stalled);
  EXPECT_EQ(first.data.size(), tp::kUsbDeviceDescriptorSize);
  EXPECT_FALSE(host.out(standard_out(UsbRecipient::kDevice, usb_request::kSetAddress, 23, 0), {}).stalled);
  EXPECT_EQ(controller.address, 23);
  EXPECT_EQ(host.in(get_descriptor(tp::kUsbDescriptorDevice, 0, 18)).data, first.data);
  const ControlResult head = host.in(get_descriptor(tp::kUsbDescriptorConfiguration, 0, 9));
  EXPECT_EQ(head.data.size(), tp::kUsbConfigurationHeaderSize);
  const uint16_t total = head.data.size() >= 4 ? static_cast<uint16_t>(head.data[2] | head.data[3] << 8) : 0;
  const ControlResult config = host.in(get_descriptor(tp::kUsbDescriptorConfiguration, 0, total));
  EXPECT_EQ(config.data.size(), total);
  for (uint8_t s : {0, 2, 1, 3}) {
    EXPECT_FALSE(host.in(get_descriptor(tp::kUsbDescriptorString, s, 255, s == 0 ? 0 : 0x0409)).stalled)
        << "string " << int(s);
  }
  EXPECT_FALSE(host.out(standard_out(UsbRecipient::kDevice, usb_request::kSetConfiguration, 1, 0), {}).stalled);
  EXPECT_TRUE(controller.configured);
  return config.data;
}

std::string string_of(const std::vector<uint8_t>& d) {
  std::string s;
  for (size_t i = 2; i + 1 < d.size(); i += 2) s.push_back(static_cast<char>(d[i]));
  return s;
}

}  // namespace tetrapulse::fw::testing
