#pragma once
// What a host needs from a tetrapulse board's USB configuration descriptor (protocol/
// SPEC.md §5.2, §5.6): the message interface and its bulk endpoints, and the DFU
// interface with its functional descriptor. Endpoint addresses are read, never assumed:
// a UDC may renumber them (a FunctionFS gadget asked for 0x01/0x81 came out as 0x02/0x81).
#include <cstdint>
#include <optional>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/bytes.hpp"

namespace tetrapulse::host {

struct UsbMessageInterface {
  uint8_t number = 0;          // wIndex of the vendor requests
  uint8_t bulk_out = 0;        // endpoint addresses as the device reports them
  uint8_t bulk_in = 0;
  uint16_t out_packet_size = 64;  // wMaxPacketSize (64 at full speed, 512 at high speed)
  uint16_t in_packet_size = 64;
};

struct DfuFunctional {
  uint8_t attributes = 0;          // bmAttributes (protocol/dfu.hpp kDfuCanDownload ...)
  uint16_t detach_timeout_ms = 0;  // wDetachTimeOut
  uint16_t transfer_size = 0;      // wTransferSize: bytes per DFU_DNLOAD
  uint16_t dfu_version = 0;        // bcdDFUVersion
};

struct UsbDfuInterface {
  uint8_t number = 0;
  bool dfu_mode = false;                     // protocol 2 (bootloader); false: run-time (protocol 1)
  std::optional<DfuFunctional> functional;   // absent from Linux 6.1 FunctionFS gadgets
};

struct UsbLayout {
  uint8_t configuration_value = 1;
  std::optional<UsbMessageInterface> messages;  // interface FF/54/01 with one bulk OUT and one bulk IN
  std::optional<UsbDfuInterface> dfu;           // interface FE/01/01 or FE/01/02
};

// Parses a whole GET_DESCRIPTOR(CONFIGURATION) answer. kMalformed (naming the offset) for a
// descriptor that runs past the end, a zero or short bLength, or wTotalLength that
// disagrees with the bytes; unknown descriptors are skipped.
HostResult<UsbLayout> parse_usb_layout(protocol::ByteView configuration);

}  // namespace tetrapulse::host
