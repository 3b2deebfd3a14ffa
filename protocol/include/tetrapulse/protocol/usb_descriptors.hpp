#pragma once
// USB descriptors of a tetrapulse board, built from one parameter set so that the
// STM32 firmware, the Linux FunctionFS gadget and the tests send the same bytes.
// Layouts: USB 2.0 §9.6 (tables 9-8, 9-10, 9-12, 9-13, 9-15) and DFU 1.1 §4.1.3.
//
// Application (PID 0x0001), 50-byte configuration:
//   configuration (9) · interface 0 vendor 0xFF/0x54/0x01 (9) · bulk OUT (7) · bulk IN (7)
//   · interface 1 DFU run-time 0xFE/0x01/0x01 (9) · DFU functional (9)
// Bootloader (PID 0x0002), 27-byte configuration:
//   configuration (9) · interface 0 DFU mode 0xFE/0x01/0x02 (9) · DFU functional (9)
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/result.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol {

enum class UsbMode : uint8_t { kApplication, kBootloader };

struct UsbDeviceParams {
  UsbMode mode = UsbMode::kApplication;
  uint16_t bcd_device = 0x0100;      // firmware version as BCD, 0xMMmm
  uint8_t max_power_2ma = 50;        // bMaxPower: current drawn from VBUS in 2 mA units
  bool self_powered = false;
  uint8_t bulk_out_address = kUsbBulkOutEndpoint;
  uint8_t bulk_in_address = kUsbBulkInEndpoint;
  uint8_t dfu_attributes = kDfuDefaultAttributes;
  uint16_t dfu_detach_timeout_ms = 1000;  // longest wait for a USB reset after DFU_DETACH
  uint16_t dfu_transfer_size = 1024;      // bytes per DFU_DNLOAD
  // Linux 6.1 FunctionFS rejects descriptors of type 0x21 outside HID/CCID; a gadget
  // on such a kernel leaves it out (dfu-util then needs -t <transfer size>).
  bool dfu_functional_descriptor = true;
};

constexpr size_t kUsbDeviceDescriptorSize = 18;
constexpr size_t kUsbConfigurationHeaderSize = 9;
constexpr size_t kUsbInterfaceDescriptorSize = 9;
constexpr size_t kUsbEndpointDescriptorSize = 7;
constexpr size_t kUsbMaxConfigurationSize = 64;  // enough for either mode

constexpr uint8_t kUsbDescriptorDevice = 1;
constexpr uint8_t kUsbDescriptorConfiguration = 2;
constexpr uint8_t kUsbDescriptorString = 3;
constexpr uint8_t kUsbDescriptorInterface = 4;
constexpr uint8_t kUsbDescriptorEndpoint = 5;
constexpr uint8_t kUsbEndpointBulk = 0x02;

// All builders return the size written, or kBufferTooSmall (nothing usable written).
Result<size_t> build_usb_device_descriptor(const UsbDeviceParams& p, uint8_t* out, size_t capacity);
// The interface, endpoint and DFU functional descriptors that follow the configuration
// descriptor: what a FunctionFS gadget writes to ep0.
Result<size_t> build_usb_function_descriptors(const UsbDeviceParams& p, uint8_t* out, size_t capacity);
// The full GET_DESCRIPTOR(CONFIGURATION) answer: configuration descriptor then the above.
Result<size_t> build_usb_configuration_descriptor(const UsbDeviceParams& p, uint8_t* out,
                                                  size_t capacity);
// String descriptor 0: the supported languages (US English only).
Result<size_t> build_usb_language_descriptor(uint8_t* out, size_t capacity);
// A string descriptor from a NUL-terminated ASCII string (UTF-16LE on the wire, at
// most 126 characters); kBadValue for a non-ASCII byte or a longer string.
Result<size_t> build_usb_string_descriptor(const char* ascii, uint8_t* out, size_t capacity);

}  // namespace tetrapulse::protocol
