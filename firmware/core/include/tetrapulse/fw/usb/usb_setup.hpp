#pragma once
// The 8-byte SETUP packet that starts every USB control transfer (USB 2.0 §9.3, table
// 9-2) and the standard request codes (table 9-4). Multi-byte fields are little-endian.
#include <cstddef>
#include <cstdint>

namespace tetrapulse::fw {

constexpr size_t kUsbSetupSize = 8;

enum class UsbRequestType : uint8_t { kStandard = 0, kClass = 1, kVendor = 2, kReserved = 3 };
enum class UsbRecipient : uint8_t { kDevice = 0, kInterface = 1, kEndpoint = 2, kOther = 3 };

struct UsbSetup {
  uint8_t request_type = 0;  // bmRequestType: bit 7 direction, bits 6..5 type, 4..0 recipient
  uint8_t request = 0;       // bRequest
  uint16_t value = 0;        // wValue
  uint16_t index = 0;        // wIndex (interface number or endpoint address in its low byte)
  uint16_t length = 0;       // wLength: the most bytes the data stage may carry

  bool device_to_host() const { return (request_type & 0x80u) != 0; }
  UsbRequestType type() const { return static_cast<UsbRequestType>((request_type >> 5) & 3u); }
  // Recipients 4..31 are reserved and come back as kOther.
  UsbRecipient recipient() const {
    const uint8_t r = request_type & 0x1Fu;
    return r <= 3 ? static_cast<UsbRecipient>(r) : UsbRecipient::kOther;
  }
};

UsbSetup decode_usb_setup(const uint8_t (&packet)[kUsbSetupSize]);
void encode_usb_setup(const UsbSetup& setup, uint8_t (&packet)[kUsbSetupSize]);

// Standard requests (bRequest with type kStandard).
namespace usb_request {
constexpr uint8_t kGetStatus = 0;
constexpr uint8_t kClearFeature = 1;
constexpr uint8_t kSetFeature = 3;
constexpr uint8_t kSetAddress = 5;
constexpr uint8_t kGetDescriptor = 6;
constexpr uint8_t kSetDescriptor = 7;
constexpr uint8_t kGetConfiguration = 8;
constexpr uint8_t kSetConfiguration = 9;
constexpr uint8_t kGetInterface = 10;
constexpr uint8_t kSetInterface = 11;
}  // namespace usb_request

// Feature selectors (table 9-6).
constexpr uint16_t kUsbFeatureEndpointHalt = 0;
constexpr uint16_t kUsbFeatureRemoteWakeup = 1;

}  // namespace tetrapulse::fw
