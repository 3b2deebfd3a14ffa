#include "tetrapulse/protocol/crc.hpp"

#include <array>

namespace tetrapulse::protocol {
namespace {

constexpr std::array<uint32_t, 256> make_crc32c_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    table[i] = c;
  }
  return table;
}

constexpr std::array<uint16_t, 256> make_crc16_table() {
  std::array<uint16_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i << 8;
    for (int k = 0; k < 8; ++k) c = (c & 0x8000u) ? (c << 1) ^ 0x1021u : c << 1;
    table[i] = static_cast<uint16_t>(c);
  }
  return table;
}

constexpr auto kCrc32cTable = make_crc32c_table();
constexpr auto kCrc16Table = make_crc16_table();

}  // namespace

void Crc32c::update(const uint8_t* data, size_t size) {
  uint32_t c = state_;
  for (size_t i = 0; i < size; ++i) c = kCrc32cTable[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  state_ = c;
}

uint32_t crc32c(const uint8_t* data, size_t size) {
  Crc32c crc;
  crc.update(data, size);
  return crc.value();
}

void Crc16Ccitt::update(const uint8_t* data, size_t size) {
  uint16_t c = state_;
  for (size_t i = 0; i < size; ++i) {
    c = static_cast<uint16_t>((c << 8) ^ kCrc16Table[((c >> 8) ^ data[i]) & 0xFFu]);
  }
  state_ = c;
}

uint16_t crc16_ccitt(const uint8_t* data, size_t size) {
  Crc16Ccitt crc;
  crc.update(data, size);
  return crc.value();
}

}  // namespace tetrapulse::protocol
