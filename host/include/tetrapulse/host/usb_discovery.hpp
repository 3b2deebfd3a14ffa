#pragma once
// Finding tetrapulse boards on USB (protocol/SPEC.md §5.1). VID:PID 1209:0001/0002 are
// pid.codes *test* PIDs shared with other people's devices, so a device counts as a board
// only when the product string is "tetrapulse" and (application) interface FF/54/01 answers
// PROTOCOL_INFO with protocol version 1, or (bootloader) its only interface is DFU mode.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::host {

struct UsbBoardListing {
  std::string serial;  // the serial number string, how --usb names a board
  protocol::UsbMode mode = protocol::UsbMode::kApplication;
  uint8_t bus = 0;
  uint8_t address = 0;
  std::string port;  // "1-1.2": bus and port path
  std::optional<protocol::UsbProtocolInfo> protocol_info;  // application mode, from the handshake
  // Empty for a board. Otherwise why a device with our VID:PID is not taken for one
  // ("product string is 'foo'", "cannot open: permission denied").
  std::string problem;
};

// Every device with VID 0x1209 and PID 0x0001 or 0x0002, each checked as above.
// kOpenFailed when libusb cannot start.
HostResult<std::vector<UsbBoardListing>> list_usb_boards();

// "usb:SERIAL" ("usb" for the only board).
std::string usb_link_name(const std::string& serial);

}  // namespace tetrapulse::host
