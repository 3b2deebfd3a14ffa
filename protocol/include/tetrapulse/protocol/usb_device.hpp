#pragma once
// The tetrapulse USB device (full speed): identifiers, interfaces, vendor control
// requests and the PROTOCOL_INFO answer. SPEC.md §5.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// pid.codes (open-source VID). 0x0001 and 0x0002 are pid.codes *test* PIDs, for
// in-house testing only: request a registered PID before boards are distributed.
// Because other test devices share these PIDs, a host also checks the product
// string and the PROTOCOL_INFO handshake before it treats a device as a board.
constexpr uint16_t kUsbVendorId = 0x1209;
constexpr uint16_t kUsbProductIdApplication = 0x0001;
constexpr uint16_t kUsbProductIdBootloader = 0x0002;  // DFU mode
constexpr char kUsbManufacturerString[] = "tetrapulse";
constexpr char kUsbProductString[] = "tetrapulse";
constexpr char kUsbDfuInterfaceString[] = "tetrapulse firmware";

// String descriptor indices (0 is the language list).
constexpr uint8_t kUsbStringManufacturer = 1;
constexpr uint8_t kUsbStringProduct = 2;
constexpr uint8_t kUsbStringSerial = 3;
constexpr uint8_t kUsbStringDfuInterface = 4;
constexpr uint16_t kUsbLanguageEnglishUs = 0x0409;

constexpr uint8_t kUsbMaxPacketSize = 64;  // full speed: endpoint 0 and both bulk endpoints

// Interface 0: messages.
constexpr uint8_t kUsbMessageInterface = 0;
constexpr uint8_t kUsbMessageInterfaceClass = 0xFF;     // vendor specific
constexpr uint8_t kUsbMessageInterfaceSubclass = 0x54;  // 'T'
constexpr uint8_t kUsbMessageInterfaceProtocol = 0x01;  // this protocol, version 1
// Endpoint addresses the device asks for. A UDC (Linux FunctionFS gadgets) may
// renumber them: hosts read the addresses from the configuration descriptor.
constexpr uint8_t kUsbBulkOutEndpoint = 0x01;
constexpr uint8_t kUsbBulkInEndpoint = 0x81;
// Interface 1 in the application: DFU run-time. In the bootloader the DFU-mode
// interface is interface 0 and the only one.
constexpr uint8_t kUsbDfuRuntimeInterface = 1;

// Vendor control requests to interface 0 (wIndex = its interface number).
constexpr uint8_t kUsbVendorRequestTypeIn = 0xC1;   // device to host, vendor, interface
constexpr uint8_t kUsbVendorRequestTypeOut = 0x41;  // host to device, vendor, interface
enum class UsbVendorRequest : uint8_t {
  kProtocolInfo = 0x01,  // IN, wLength >= 8: UsbProtocolInfo
  kMessageOut = 0x02,    // OUT, wLength = message size: one message in the data stage
  kMessageIn = 0x03,     // IN, wLength = kMaxMessageSize: oldest pending message, or none (0 bytes)
};

// Capability bits of PROTOCOL_INFO.
constexpr uint32_t kUsbCapabilityBulkMessages = 1u << 0;     // messages on the bulk endpoints
constexpr uint32_t kUsbCapabilityControlMessages = 1u << 1;  // MESSAGE_OUT / MESSAGE_IN
constexpr uint32_t kUsbCapabilityDfuRuntime = 1u << 2;       // DFU run-time interface present

// PROTOCOL_INFO answer:
//   0 protocol version u8  1 reserved u8 (0)  2 max message size u16  4 capabilities u32
// Later versions may append fields; readers ignore what follows the 8 bytes.
struct UsbProtocolInfo {
  uint8_t protocol_version = kProtocolVersion;
  uint16_t max_message_size = static_cast<uint16_t>(kMaxMessageSize);
  uint32_t capabilities = 0;

  bool operator==(const UsbProtocolInfo& o) const {
    return protocol_version == o.protocol_version && max_message_size == o.max_message_size &&
           capabilities == o.capabilities;
  }
};
constexpr size_t kUsbProtocolInfoSize = 8;

Result<size_t> encode_usb_protocol_info(const UsbProtocolInfo& info, uint8_t* out, size_t capacity);
// kTruncated under 8 bytes.
Result<UsbProtocolInfo> decode_usb_protocol_info(ByteView in);

}  // namespace tetrapulse::protocol
