#pragma once
// Messages in vendor control transfers to interface 0 (SPEC.md §5.3): MESSAGE_OUT carries
// one message in its OUT data stage (wLength = the message size), MESSAGE_IN the oldest
// pending message in its IN data stage.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/receive_event.hpp"
#include "tetrapulse/protocol/result.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol {

// MESSAGE_OUT setup stage: kBadLength (the device stalls) unless 3 <= wLength <= kMaxMessageSize.
Status check_usb_message_out(uint16_t w_length);

// Collects a MESSAGE_OUT data stage from endpoint 0 OUT packets, for a device whose
// controller hands over packets (STM32 OTG FS).
class UsbMessageOutReceiver {
 public:
  // The setup stage; errors as check_usb_message_out (then nothing is expected).
  Status begin(uint16_t w_length);
  // One data-stage packet: kNothing until wLength bytes have arrived, then kMessage with
  // them. kError, after which the next begin() is awaited: kBadFraming for a packet over
  // 64 bytes or one with no MESSAGE_OUT begun, kTruncated for a short packet that ends
  // the data stage before wLength, kBadLength for bytes past wLength.
  ReceiveEvent push_packet(ByteView packet);
  void reset();

 private:
  size_t expected_ = 0;  // wLength of the stage in progress, 0 when none
  size_t size_ = 0;
  uint8_t buffer_[kMaxMessageSize] = {};
};

// MESSAGE_IN for a pending message of `pending_size` bytes (0: none pending) asked with
// `w_length`: kBufferTooSmall when wLength is shorter than the message (the device stalls
// and the message stays pending).
Status check_usb_message_in(uint16_t w_length, size_t pending_size);

// An IN data stage of `size` bytes asked with `w_length` ends with a zero-length packet
// when it is shorter than wLength and fills whole packets (USB 2.0 §5.5.3); an empty
// stage is one zero-length packet.
constexpr bool usb_control_in_needs_zlp(size_t size, uint16_t w_length) {
  return size < w_length && size % kUsbMaxPacketSize == 0;
}

}  // namespace tetrapulse::protocol
