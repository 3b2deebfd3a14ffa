#pragma once
// Firmware images for the Linux board (SPEC.md §7): hw_model 2 (linux), revisions
// 0..255, load_address 0 (either slot), vector_offset 128, the payload after it. The
// board checks header and payload CRC-32C like any board and reports the version of the
// slot it boots; it does not execute the payload (the daemon is the program; the image
// is what its flash holds), so a release may carry any payload, e.g. the daemon binary.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tetrapulse::linux_board {

std::vector<uint8_t> make_linux_image(uint32_t fw_version, const std::vector<uint8_t>& payload);
// `count` bytes of a seeded sequence (stand-in payloads for tests).
std::vector<uint8_t> seeded_payload(size_t count, uint32_t seed);
// "1.2.3" as pack_version(1, 2, 3); nullopt when malformed or out of range.
std::optional<uint32_t> parse_version(const std::string& text);

}  // namespace tetrapulse::linux_board
