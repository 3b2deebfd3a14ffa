#pragma once
// The arithmetic of the OTG FS driver (usb_otg_fs.hpp) that is not a register access, so
// that host tests can check it: how the core's 320 words of FIFO RAM are shared, which
// hardware endpoints the descriptors' bulk addresses name, how an IN transfer is cut into
// packets, and how bytes go into 32-bit FIFO words (little-endian, RM0090 §34.11).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::stm32f405 {

constexpr size_t kOtgFifoWords = 320;      // 1.25 KB of FIFO RAM in the OTG FS core
constexpr unsigned kOtgEndpoints = 4;      // EP0..EP3 in each direction
constexpr size_t kOtgMinTxFifoWords = 16;  // RM0090 DIEPTXFx: INEPTXFD minimum

// Receive FIFO words RM0090 §34.11.3 asks for: 13 for SETUP packets and their status
// (one control endpoint), one largest packet plus its status word, 2 per OUT endpoint
// for transfer-complete entries, one for the global OUT NAK.
constexpr size_t min_rx_fifo_words(size_t largest_packet, unsigned out_endpoints) {
  return (5 * 1 + 8) + (largest_packet / 4 + 1) + 2 * out_endpoints + 1;
}

// Word offsets and depths of the FIFOs: receive at 0, then EP0's transmit FIFO, then the
// bulk IN endpoint's, deep enough for a whole bulk transfer (SPEC §5.4: 322 bytes) so that
// an answer is written in one go.
struct FifoPlan {
  uint16_t rx_words = 128;  // SETUPs and several 64-byte OUT packets
  uint16_t tx0_start = 128;
  uint16_t tx0_words = 32;
  uint16_t bulk_in_start = 160;
  uint16_t bulk_in_words = 128;
};
constexpr FifoPlan kFifoPlan{};

constexpr size_t words_for(size_t bytes) { return (bytes + 3) / 4; }

// True when the FIFOs follow each other without overlap inside the RAM, each at least its
// minimum, EP0's holds a packet and the bulk IN one a whole transfer.
constexpr bool plan_fits(const FifoPlan& p) {
  return p.rx_words >= min_rx_fifo_words(protocol::kUsbMaxPacketSize, 2) && p.tx0_start == p.rx_words &&
         p.tx0_words >= kOtgMinTxFifoWords && p.tx0_words >= words_for(protocol::kUsbMaxPacketSize) &&
         p.bulk_in_start == p.tx0_start + p.tx0_words && p.bulk_in_words >= kOtgMinTxFifoWords &&
         p.bulk_in_words >= words_for(protocol::kUsbBulkMaxTransfer) &&
         size_t{p.bulk_in_start} + p.bulk_in_words <= kOtgFifoWords;
}
static_assert(plan_fits(kFifoPlan));

// The hardware endpoint numbers behind the bulk addresses the configuration descriptor
// carries (UsbDeviceParams, the same parameters the descriptor builders read).
struct BulkEndpoints {
  unsigned out = 0;
  unsigned in = 0;
};

// kBadValue unless OUT is an OUT address and IN an IN address, both naming one of EP1..EP3
// (EP0 is the control endpoint) and nothing else in the address byte.
inline protocol::Result<BulkEndpoints> bulk_endpoints(const protocol::UsbDeviceParams& p) {
  const unsigned out = p.bulk_out_address;
  const unsigned in = p.bulk_in_address;
  const bool out_ok = (out & 0x80u) == 0 && out >= 1 && out < kOtgEndpoints;
  const bool in_ok = (in & 0x80u) != 0 && (in & 0x7Fu) >= 1 && (in & 0x7Fu) < kOtgEndpoints;
  if (!out_ok || !in_ok) return protocol::Error::kBadValue;
  return BulkEndpoints{out, in & 0x7Fu};
}

// One IN transfer as DIEPTSIZ takes it: `packets` (PKTCNT; a zero-length transfer is one
// packet) and `words` written to the FIFO. A transfer that ends on a packet boundary needs
// a zero-length packet after it (usb_bulk_needs_zlp), sent as a transfer of its own.
struct InTransfer {
  uint32_t packets = 1;
  uint32_t words = 0;
};

constexpr InTransfer in_transfer(size_t bytes) {
  const size_t packet = protocol::kUsbMaxPacketSize;
  return InTransfer{static_cast<uint32_t>(bytes == 0 ? 1 : (bytes + packet - 1) / packet),
                    static_cast<uint32_t>(words_for(bytes))};
}

// The FIFO word holding bytes [4*index, 4*index + 4) of `bytes` (zero past its end).
constexpr uint32_t fifo_word(protocol::ByteView bytes, size_t index) {
  uint32_t word = 0;
  for (size_t k = 0; k < 4 && 4 * index + k < bytes.size; ++k) {
    word |= static_cast<uint32_t>(bytes.data[4 * index + k]) << (8 * k);
  }
  return word;
}

// Stores the bytes of FIFO word `index` of a `count`-byte packet into `out`, keeping only
// those below `capacity` (the rest of a packet that does not fit is dropped).
constexpr void store_fifo_word(uint32_t word, size_t index, size_t count, uint8_t* out, size_t capacity) {
  for (size_t k = 0; k < 4; ++k) {
    const size_t at = 4 * index + k;
    if (at < count && at < capacity) out[at] = static_cast<uint8_t>(word >> (8 * k));
  }
}

}  // namespace tetrapulse::stm32f405
