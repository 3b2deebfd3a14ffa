#pragma once
// Firmware and bootloader versions travel as one u32: major<<24 | minor<<16 | patch.
#include <cstdint>

namespace tetrapulse::protocol {

constexpr uint32_t pack_version(uint8_t major, uint8_t minor, uint16_t patch) {
  return (static_cast<uint32_t>(major) << 24) | (static_cast<uint32_t>(minor) << 16) | patch;
}
constexpr uint8_t version_major(uint32_t v) { return static_cast<uint8_t>(v >> 24); }
constexpr uint8_t version_minor(uint32_t v) { return static_cast<uint8_t>(v >> 16); }
constexpr uint16_t version_patch(uint32_t v) { return static_cast<uint16_t>(v); }

}  // namespace tetrapulse::protocol
