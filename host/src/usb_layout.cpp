#include "tetrapulse/host/usb_layout.hpp"

#include <fmt/format.h>

#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::host {

namespace {

uint16_t u16_at(protocol::ByteView b, size_t at) {
  return static_cast<uint16_t>(b[at] | (b[at + 1] << 8));
}

tl::unexpected<HostError> malformed(const std::string& what) {
  return host_error(HostErrorKind::kMalformed, "", "configuration descriptor: " + what, protocol::Error::kBadLength);
}

}  // namespace

HostResult<UsbLayout> parse_usb_layout(protocol::ByteView c) {
  using namespace protocol;
  if (c.size < kUsbConfigurationHeaderSize || c[0] < kUsbConfigurationHeaderSize ||
      c[1] != kUsbDescriptorConfiguration) {
    return malformed("does not start with a configuration descriptor");
  }
  if (u16_at(c, 2) != c.size) {
    return malformed(fmt::format("wTotalLength {} but {} bytes", u16_at(c, 2), c.size));
  }
  UsbLayout layout;
  layout.configuration_value = c[5];
  enum class In { kOther, kMessages, kDfu } in = In::kOther;
  UsbMessageInterface messages;
  UsbDfuInterface dfu;
  bool have_dfu = false;
  size_t endpoints = 0;
  auto finish_messages = [&] {
    if (in == In::kMessages && messages.bulk_out != 0 && messages.bulk_in != 0 && endpoints == 2) {
      layout.messages = messages;
    }
  };
  for (size_t at = c[0]; at < c.size;) {
    const uint8_t length = c[at];
    if (length < 2 || at + length > c.size) {
      return malformed(fmt::format("descriptor at offset {} with bLength {} runs past {} bytes", at, length, c.size));
    }
    const uint8_t type = c[at + 1];
    if (type == kUsbDescriptorInterface) {
      if (length < kUsbInterfaceDescriptorSize) return malformed(fmt::format("short interface at offset {}", at));
      finish_messages();
      const uint8_t number = c[at + 2], alternate = c[at + 3];
      const uint8_t cls = c[at + 5], sub = c[at + 6], proto = c[at + 7];
      in = In::kOther;
      endpoints = 0;
      if (alternate != 0) {
        // Only alternate setting 0 is ours.
      } else if (cls == kUsbMessageInterfaceClass && sub == kUsbMessageInterfaceSubclass &&
                 proto == kUsbMessageInterfaceProtocol && !layout.messages) {
        in = In::kMessages;
        messages = UsbMessageInterface{};
        messages.number = number;
      } else if (cls == kDfuInterfaceClass && sub == kDfuInterfaceSubclass &&
                 (proto == kDfuProtocolRuntime || proto == kDfuProtocolDfuMode) && !have_dfu) {
        in = In::kDfu;
        dfu = UsbDfuInterface{number, proto == kDfuProtocolDfuMode, std::nullopt};
        have_dfu = true;
      }
    } else if (type == kUsbDescriptorEndpoint && in == In::kMessages) {
      if (length < kUsbEndpointDescriptorSize) return malformed(fmt::format("short endpoint at offset {}", at));
      const uint8_t address = c[at + 2];
      const uint16_t packet = static_cast<uint16_t>(u16_at(c, at + 4) & 0x7FF);
      ++endpoints;
      if ((c[at + 3] & 0x03) == kUsbEndpointBulk) {
        if ((address & 0x80) != 0) {
          messages.bulk_in = address;
          messages.in_packet_size = packet;
        } else {
          messages.bulk_out = address;
          messages.out_packet_size = packet;
        }
      }
    } else if (type == kDfuFunctionalDescriptorType && in == In::kDfu) {
      if (length < 7) return malformed(fmt::format("short DFU functional descriptor at offset {}", at));
      DfuFunctional f;
      f.attributes = c[at + 2];
      f.detach_timeout_ms = u16_at(c, at + 3);
      f.transfer_size = u16_at(c, at + 5);
      f.dfu_version = length >= 9 ? u16_at(c, at + 7) : 0x0100;
      dfu.functional = f;
    }
    at += length;
  }
  finish_messages();
  if (have_dfu) layout.dfu = dfu;
  return layout;
}

}  // namespace tetrapulse::host
