#pragma once
// The transport vector files (protocol/vectors/{can,uart,usb}, SPEC.md §4.6, §5.7, §6.4)
// as protocol objects, for the tests and the fuzz seed writer.
#include <tl/expected.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "hex_vectors.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::protocol::testing {

// One CAN transfer: [message] bytes, [transfer] priority= source= destination= transfer_id=,
// and [frame.0], [frame.1], ... each id= and its data bytes, in bus order.
struct CanTransferVector {
  std::string path;
  std::vector<uint8_t> message;
  CanTransferHeader header;
  std::vector<CanFrame> frames;
};

// The error names the file and what is missing or out of range.
tl::expected<CanTransferVector, std::string> can_transfer_vector(const HexFile& file);

// One USB descriptor set: [params] the fields of UsbDeviceParams, [device], [configuration].
struct UsbDescriptorVector {
  std::string path;
  UsbDeviceParams params;
  std::vector<uint8_t> device;
  std::vector<uint8_t> configuration;
};

// The error names the file and what is missing.
tl::expected<UsbDescriptorVector, std::string> usb_descriptor_vector(const HexFile& file);

// Every file in vectors/<folder> whose name starts with `prefix`; none is an error.
tl::expected<std::vector<HexFile>, std::string> read_vectors(const std::string& folder,
                                                             const std::string& prefix = "");

}  // namespace tetrapulse::protocol::testing
