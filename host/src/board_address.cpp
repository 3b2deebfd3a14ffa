#include "tetrapulse/host/board_address.hpp"

#include <cctype>

#include <fmt/format.h>

#include "tetrapulse/host/can_link.hpp"
#include "tetrapulse/host/serial_link.hpp"
#include "tetrapulse/host/usb_discovery.hpp"
#include "tetrapulse/host/usb_link.hpp"

namespace tetrapulse::host {
namespace {

bool all_digits(const std::string& s) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

tl::unexpected<HostError> bad(const std::string& text, const std::string& why) {
  return host_error(HostErrorKind::kBadInput, text, why);
}

}  // namespace

std::string BoardAddress::text() const {
  switch (kind) {
    case Kind::kUsb: return "usb:" + usb_serial;
    case Kind::kCan: return fmt::format("can:{}:{}", can_interface, node);
    case Kind::kSerial: return fmt::format("serial:{}:{}", serial_path, baud);
    case Kind::kSim: return fmt::format("sim:{}", node);
  }
  return "";
}

HostResult<uint8_t> parse_node_id(const std::string& text, const std::string& what) {
  if (!all_digits(text) || std::stoul(text) < 1 || std::stoul(text) > 254) {
    return bad(what, fmt::format("node '{}' is not a CAN node id 1..254", text));
  }
  return static_cast<uint8_t>(std::stoul(text));
}

HostResult<BoardAddress> parse_usb_address(const std::string& serial) {
  for (char c : serial) {
    if (!std::isprint(static_cast<unsigned char>(c)) || c == ' ') {
      return bad("usb:" + serial, "a USB serial number is printable text without spaces");
    }
  }
  BoardAddress a;
  a.kind = BoardAddress::Kind::kUsb;
  a.usb_serial = serial;
  return a;
}

HostResult<BoardAddress> parse_can_address(const std::string& text) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) return bad("can:" + text, "expected IFACE:NODE, e.g. can0:3");
  BoardAddress a;
  a.kind = BoardAddress::Kind::kCan;
  a.can_interface = text.substr(0, colon);
  if (a.can_interface.size() >= 16 || a.can_interface.find('/') != std::string::npos) {
    return bad("can:" + text, fmt::format("'{}' is not a network interface name", a.can_interface));
  }
  auto node = parse_node_id(text.substr(colon + 1), "can:" + text);
  if (!node) return tl::unexpected(node.error());
  a.node = *node;
  return a;
}

HostResult<BoardAddress> parse_serial_address(const std::string& text) {
  BoardAddress a;
  a.kind = BoardAddress::Kind::kSerial;
  a.serial_path = text;
  const size_t colon = text.rfind(':');
  if (colon != std::string::npos && all_digits(text.substr(colon + 1))) {
    a.serial_path = text.substr(0, colon);
    a.baud = static_cast<uint32_t>(std::stoul(text.substr(colon + 1)));
  }
  if (a.serial_path.empty()) return bad("serial:" + text, "expected PATH[:BAUD], e.g. /dev/ttyUSB0:115200");
  return a;
}

HostResult<BoardAddress> parse_sim_address(const std::string& text) {
  BoardAddress a;
  a.kind = BoardAddress::Kind::kSim;
  auto node = parse_node_id(text, "sim:" + text);
  if (!node) return tl::unexpected(node.error());
  a.node = *node;
  return a;
}

HostResult<BoardAddress> parse_board_address(const std::string& text) {
  const size_t colon = text.find(':');
  const std::string scheme = colon == std::string::npos ? text : text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (colon != std::string::npos) {
    if (scheme == "usb") return parse_usb_address(rest);
    if (scheme == "can") return parse_can_address(rest);
    if (scheme == "serial") return parse_serial_address(rest);
    if (scheme == "sim") return parse_sim_address(rest);
  }
  return bad(text, "a board is usb:SERIAL, can:IFACE:NODE, serial:PATH[:BAUD] or sim:NODE");
}

HostResult<std::unique_ptr<Link>> open_link(const BoardAddress& address) {
  switch (address.kind) {
    case BoardAddress::Kind::kUsb: {
      auto link = UsbLink::open(address.usb_serial);
      if (!link) return tl::unexpected(link.error());
      return std::unique_ptr<Link>(std::move(*link));
    }
    case BoardAddress::Kind::kCan: {
      auto link = CanLink::open(address.can_interface, address.node);
      if (!link) return tl::unexpected(link.error());
      return std::unique_ptr<Link>(std::move(*link));
    }
    case BoardAddress::Kind::kSerial: {
      auto link = SerialLink::open(address.serial_path, address.baud);
      if (!link) return tl::unexpected(link.error());
      return std::unique_ptr<Link>(std::move(*link));
    }
    case BoardAddress::Kind::kSim:
      return host_error(HostErrorKind::kNotFound, address.text(), "simulated boards open with open_sim_link()");
  }
  return host_error(HostErrorKind::kBadInput, address.text(), "unknown kind of address");
}

}  // namespace tetrapulse::host
