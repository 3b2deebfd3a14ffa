#pragma once
// How a board is named on the command line and in scripts, and opening a link to it:
//   usb:SERIAL            the USB serial number string ("usb:" alone: the only board)
//   can:IFACE:NODE        SocketCAN interface and node id 1..254
//   serial:PATH[:BAUD]    a serial port, 115200 baud unless given
//   sim:NODE              a simulated board of the virtual rig, in this process
#include <cstdint>
#include <memory>
#include <string>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/host/link.hpp"

namespace tetrapulse::host {

struct BoardAddress {
  enum class Kind { kUsb, kCan, kSerial, kSim };
  Kind kind = Kind::kUsb;
  std::string usb_serial;
  std::string can_interface;
  uint8_t node = 1;  // CAN node, or the simulated board's node id
  std::string serial_path;
  uint32_t baud = 115200;

  // The canonical text ("can:vcan0:3", "serial:/dev/ttyUSB0:115200"), which parses back to it.
  std::string text() const;
};

// "usb:…", "can:…", "serial:…" or "sim:…"; kBadInput saying what is wrong.
HostResult<BoardAddress> parse_board_address(const std::string& text);
// The parts after the prefix, as --usb, --can and --serial take them.
HostResult<BoardAddress> parse_usb_address(const std::string& serial);
HostResult<BoardAddress> parse_can_address(const std::string& interface_and_node);
HostResult<BoardAddress> parse_serial_address(const std::string& path_and_baud);
HostResult<BoardAddress> parse_sim_address(const std::string& node);

// A node id 1..254 ("3"); kBadInput otherwise.
HostResult<uint8_t> parse_node_id(const std::string& text, const std::string& what);

// Opens a link to a USB, CAN or serial board. Simulated boards live in the program that
// simulates them: open_sim_link() (sim_board_link.hpp); here they are kNotFound.
HostResult<std::unique_ptr<Link>> open_link(const BoardAddress& address);

}  // namespace tetrapulse::host
