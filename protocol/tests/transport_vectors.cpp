#include "transport_vectors.hpp"

#include <iterator>

namespace tetrapulse::protocol::testing {
namespace {

// The attribute `key` of `record` as an integer of at most `max`.
tl::expected<uint64_t, std::string> bounded(const HexRecord& record, const std::string& key, uint64_t max) {
  auto value = record.number(key);
  if (value && *value > max) {
    return tl::make_unexpected(record.origin + ": [" + record.name + "] " + key + " over " + std::to_string(max));
  }
  return value;
}

}  // namespace

tl::expected<CanTransferVector, std::string> can_transfer_vector(const HexFile& file) {
  const HexRecord* message = file.find("message");
  const HexRecord* transfer = file.find("transfer");
  const auto frames = file.starting_with("frame.");
  if (message == nullptr || transfer == nullptr || frames.empty()) {
    return tl::make_unexpected(file.path + ": a CAN vector needs [message], [transfer] and [frame.N] records");
  }
  CanTransferVector v;
  v.path = file.path;
  v.message = message->bytes;
  const auto priority = bounded(*transfer, "priority", 7);
  const auto source = bounded(*transfer, "source", 0xFF);
  const auto destination = bounded(*transfer, "destination", 0xFF);
  const auto transfer_id = bounded(*transfer, "transfer_id", kCanTransferIdModulo - 1);
  for (const auto* field : {&priority, &source, &destination, &transfer_id}) {
    if (!*field) return tl::make_unexpected(field->error());
  }
  v.header = CanTransferHeader{static_cast<uint8_t>(*priority), static_cast<uint8_t>(*destination),
                               static_cast<uint8_t>(*source), static_cast<uint8_t>(*transfer_id)};
  for (const HexRecord* r : frames) {
    const auto id = bounded(*r, "id", 0xFFFFFFFF);
    if (!id) return tl::make_unexpected(id.error());
    if (r->bytes.size() > kCanFrameDataSize) {
      return tl::make_unexpected(r->origin + ": [" + r->name + "] holds more than 8 data bytes");
    }
    CanFrame frame;
    frame.id = static_cast<uint32_t>(*id);
    for (uint8_t b : r->bytes) frame.data[frame.size++] = b;
    v.frames.push_back(frame);
  }
  return v;
}

tl::expected<UsbDescriptorVector, std::string> usb_descriptor_vector(const HexFile& file) {
  const HexRecord* params = file.find("params");
  const HexRecord* device = file.find("device");
  const HexRecord* configuration = file.find("configuration");
  if (params == nullptr || device == nullptr || configuration == nullptr) {
    return tl::make_unexpected(file.path + ": a descriptor vector needs [params], [device] and [configuration]");
  }
  const char* const keys[] = {"bootloader",     "bcd_device",        "max_power_2ma", "self_powered",
                              "bulk_out",       "bulk_in",           "dfu_attributes", "detach_timeout_ms",
                              "transfer_size",  "dfu_functional"};
  uint64_t v[std::size(keys)] = {};
  for (size_t i = 0; i < std::size(keys); ++i) {
    const auto n = bounded(*params, keys[i], 0xFFFF);
    if (!n) return tl::make_unexpected(n.error());
    v[i] = *n;
  }
  UsbDescriptorVector d;
  d.path = file.path;
  d.params.mode = v[0] != 0 ? UsbMode::kBootloader : UsbMode::kApplication;
  d.params.bcd_device = static_cast<uint16_t>(v[1]);
  d.params.max_power_2ma = static_cast<uint8_t>(v[2]);
  d.params.self_powered = v[3] != 0;
  d.params.bulk_out_address = static_cast<uint8_t>(v[4]);
  d.params.bulk_in_address = static_cast<uint8_t>(v[5]);
  d.params.dfu_attributes = static_cast<uint8_t>(v[6]);
  d.params.dfu_detach_timeout_ms = static_cast<uint16_t>(v[7]);
  d.params.dfu_transfer_size = static_cast<uint16_t>(v[8]);
  d.params.dfu_functional_descriptor = v[9] != 0;
  d.device = device->bytes;
  d.configuration = configuration->bytes;
  return d;
}

tl::expected<std::vector<HexFile>, std::string> read_vectors(const std::string& folder, const std::string& prefix) {
  auto files = read_hex_folder(vectors_dir() + "/" + folder);
  if (!files) return files;
  std::vector<HexFile> chosen;
  for (HexFile& f : *files) {
    if (f.stem.compare(0, prefix.size(), prefix) == 0) chosen.push_back(std::move(f));
  }
  if (chosen.empty()) return tl::make_unexpected(vectors_dir() + "/" + folder + ": no " + prefix + "*.hex files");
  return chosen;
}

}  // namespace tetrapulse::protocol::testing
