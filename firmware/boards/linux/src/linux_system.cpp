#include "tetrapulse/linux_board/linux_system.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <fstream>

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::linux_board {

std::string serial_text(const BoardSerial& serial) {
  std::string text;
  char hex[3];
  for (uint8_t b : serial) {
    std::snprintf(hex, sizeof(hex), "%02X", b);
    text += hex;
  }
  return text;
}

std::optional<BoardSerial> parse_serial(const std::string& text) {
  if (text.size() != 2 * protocol::kSerialSize) return std::nullopt;
  BoardSerial serial{};
  for (size_t i = 0; i < serial.size(); ++i) {
    unsigned value = 0;
    for (size_t k = 0; k < 2; ++k) {
      const char c = text[2 * i + k];
      if (std::isxdigit(static_cast<unsigned char>(c)) == 0) return std::nullopt;
      value = value * 16 + static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(c)) != 0
                                                     ? c - '0'
                                                     : std::tolower(static_cast<unsigned char>(c)) - 'a' + 10);
    }
    serial[i] = static_cast<uint8_t>(value);
  }
  return serial;
}

BoardSerial machine_serial() {
  std::string id;
  std::ifstream("/etc/machine-id") >> id;
  if (auto s = parse_serial(id.substr(0, 2 * protocol::kSerialSize)); s && id.size() >= 2 * protocol::kSerialSize) {
    return *s;
  }
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  BoardSerial serial{};
  uint32_t h = protocol::crc32c(reinterpret_cast<const uint8_t*>(host), std::char_traits<char>::length(host));
  for (size_t i = 0; i < serial.size(); ++i) {
    if (i % 4 == 0 && i > 0) h = protocol::crc32c(reinterpret_cast<const uint8_t*>(&h), sizeof(h));
    serial[i] = static_cast<uint8_t>(h >> (8 * (i % 4)));
  }
  return serial;
}

uint32_t LinuxSystem::do_bootloader_version() const { return protocol::pack_version(1, 0, 0); }

}  // namespace tetrapulse::linux_board
