#include "tetrapulse/host/firmware_image.hpp"

#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::host {

using protocol::HwModel;

const char* hw_model_name(HwModel model) {
  switch (model) {
    case HwModel::kStm32f405Reference: return "stm32f405";
    case HwModel::kLinuxBoard: return "linux";
    case HwModel::kSimulatedBoard: return "sim";
  }
  return "unknown";
}

HostResult<FirmwareImage> check_firmware_image(std::vector<uint8_t> bytes, const std::string& name) {
  const protocol::ByteView view{bytes.data(), bytes.size()};
  const protocol::Result<protocol::ImageHeader> header = protocol::decode_image_header(view);
  if (!header) {
    return host_error(HostErrorKind::kBadFile, name,
                      fmt::format("not a tetrapulse firmware image: header {}", protocol::error_name(header.error())),
                      header.error());
  }
  if (protocol::image_size(*header) != bytes.size()) {
    return host_error(HostErrorKind::kBadFile, name,
                      fmt::format("header says {} bytes, the file has {}", protocol::image_size(*header), bytes.size()),
                      protocol::Error::kBadLength);
  }
  if (!protocol::check_payload(*header, view)) {
    return host_error(HostErrorKind::kBadFile, name, "payload CRC-32C does not match the header", protocol::Error::kBadCrc);
  }
  FirmwareImage image;
  image.name = name;
  image.header = *header;
  image.crc32c = protocol::crc32c(bytes.data(), bytes.size());
  image.bytes = std::move(bytes);
  return image;
}

HostResult<FirmwareImage> read_firmware_image(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return host_error(HostErrorKind::kBadFile, path, "cannot read the file");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return host_error(HostErrorKind::kBadFile, path, "read error");
  return check_firmware_image(std::move(bytes), path);
}

std::optional<SlotLayout> slot_layout(HwModel model) {
  switch (model) {
    case HwModel::kStm32f405Reference: return SlotLayout{{0x08020000u, 0x08040000u}, 128u * 1024u};
    case HwModel::kLinuxBoard: return SlotLayout{{0, 0}, 0};
    case HwModel::kSimulatedBoard: return SlotLayout{{0, 0}, 16u * 1024u};
  }
  return std::nullopt;
}

HostResult<const FirmwareImage*> choose_image(const std::vector<FirmwareImage>& images, const protocol::Info& board,
                                              const std::string& board_name) {
  const std::optional<SlotLayout> layout = slot_layout(board.hw_model);
  if (!layout) {
    return host_error(HostErrorKind::kImageRejected, board_name,
                      fmt::format("unknown hardware model {}", static_cast<unsigned>(board.hw_model)));
  }
  if (board.active_slot > 1) {
    return host_error(HostErrorKind::kImageRejected, board_name,
                      fmt::format("runs from slot {}, which this host does not know", board.active_slot));
  }
  const uint32_t wanted = layout->base[1 - board.active_slot];
  std::string reasons;
  for (const FirmwareImage& image : images) {
    const protocol::ImageHeader& h = image.header;
    std::string why;
    if (!protocol::fits(h, board.hw_model, board.hw_revision)) {
      why = fmt::format("built for {} rev {}..{}, the board is {} rev {}", hw_model_name(h.hw_model), h.hw_revision_min,
                        h.hw_revision_max, hw_model_name(board.hw_model), board.hw_revision);
    } else if (h.load_address != wanted) {
      why = fmt::format("linked for 0x{:08X}, the board runs slot {} and takes an image for slot {} at 0x{:08X}",
                        h.load_address, board.active_slot, 1 - board.active_slot, wanted);
    } else if (layout->capacity != 0 && image.bytes.size() > layout->capacity) {
      why = fmt::format("{} bytes, a slot holds {}", image.bytes.size(), layout->capacity);
    } else {
      return &image;
    }
    reasons += fmt::format("{}{}: {}", reasons.empty() ? "" : "; ", image.name, why);
  }
  if (images.empty()) reasons = "no image given";
  return host_error(HostErrorKind::kImageRejected, board_name, "no image fits: " + reasons, protocol::Error::kImageRejected);
}

}  // namespace tetrapulse::host
