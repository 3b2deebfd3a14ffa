#pragma once
// Host-side conveniences for transport tests: what a bus carries for one transfer.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol::testing {

// The packets of one USB transfer (bulk, or a control data stage): 64-byte packets, then
// a short one; a transfer that fills whole packets ends with a zero-length packet when
// `zlp` is set (always on bulk, SPEC.md §5.4; on a control stage only when it is shorter
// than wLength, §5.3).
inline std::vector<std::vector<uint8_t>> usb_packets(const std::vector<uint8_t>& transfer, bool zlp = true) {
  std::vector<std::vector<uint8_t>> packets;
  for (size_t at = 0; at <= transfer.size(); at += kUsbMaxPacketSize) {
    const size_t n = std::min<size_t>(kUsbMaxPacketSize, transfer.size() - at);
    if (n == 0 && !zlp && at > 0) break;
    packets.emplace_back(transfer.begin() + static_cast<long>(at), transfer.begin() + static_cast<long>(at + n));
    if (n < kUsbMaxPacketSize) break;
  }
  return packets;
}

}  // namespace tetrapulse::protocol::testing
