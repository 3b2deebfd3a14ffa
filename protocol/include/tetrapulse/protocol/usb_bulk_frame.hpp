#pragma once
// USB bulk framing (SPEC.md §5.4): one message per bulk transfer, as
// [length u16 little-endian][message]. A transfer ends with a short packet, so one
// whose size is a multiple of the 64-byte packet size is followed by a zero-length
// packet (ZLP).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/receive_event.hpp"
#include "tetrapulse/protocol/result.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol {

constexpr size_t kUsbBulkHeaderSize = 2;
constexpr size_t kUsbBulkMaxTransfer = kUsbBulkHeaderSize + kMaxMessageSize;
// Read buffer for a host: a whole number of packets no smaller than the largest
// transfer, so that a device can never overflow it.
constexpr size_t kUsbBulkReadSize =
    (kUsbBulkMaxTransfer + kUsbMaxPacketSize - 1) / kUsbMaxPacketSize * kUsbMaxPacketSize;

// True when a transfer of `size` bytes must be followed by a zero-length packet.
constexpr bool usb_bulk_needs_zlp(size_t size) { return size % kUsbMaxPacketSize == 0; }
// Packets a transfer of `size` bytes takes on the bus, the ZLP included.
constexpr size_t usb_bulk_packet_count(size_t size) { return size / kUsbMaxPacketSize + 1; }

// Writes [length][message]; kBadLength unless 3 <= message.size <= kMaxMessageSize,
// kBufferTooSmall when capacity < message.size + 2.
Result<size_t> encode_usb_bulk_frame(ByteView message, uint8_t* out, size_t capacity);

// The message in one received transfer. kTruncated under 2 bytes; kBadLength when the
// length field is not (transfer size - 2), exceeds kMaxMessageSize or is under 3.
Result<ByteView> decode_usb_bulk_frame(ByteView transfer);

// Rebuilds transfers from packets, for a device whose controller hands over packets
// (STM32 OTG FS). A packet shorter than 64 bytes ends the transfer. A transfer that
// grows past kUsbBulkMaxTransfer is reported (kBadLength) once and skipped up to its
// short packet; a packet over 64 bytes is kBadFraming. A lone ZLP is ignored.
class UsbBulkFrameReceiver {
 public:
  ReceiveEvent push_packet(ByteView packet);
  void reset();

 private:
  size_t size_ = 0;
  bool skipping_ = false;
  uint8_t buffer_[kUsbBulkMaxTransfer] = {};
};

}  // namespace tetrapulse::protocol
