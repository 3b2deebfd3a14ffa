#include "transport_vectors.hpp"

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
