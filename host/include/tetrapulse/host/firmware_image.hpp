#pragma once
// Firmware images as the host handles them (protocol/SPEC.md §7): read and checked from
// files, and matched to a board. Images are linked per slot, so a release carries one
// image per slot; the board takes the one built for its model and revision whose
// load_address is the base of the slot that is not running.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::host {

struct FirmwareImage {
  std::string name;  // the file it came from
  std::vector<uint8_t> bytes;
  protocol::ImageHeader header;
  uint32_t crc32c = 0;  // of the whole image (UpdateBegin.crc32c)
};

// Checks an image: the header decodes, the file holds exactly vector_offset + payload_size
// bytes, the payload CRC matches. kBadFile naming `name` and what is wrong.
HostResult<FirmwareImage> check_firmware_image(std::vector<uint8_t> bytes, const std::string& name);
HostResult<FirmwareImage> read_firmware_image(const std::string& path);

// Where a board model keeps its two application slots: the load_address an image needs in
// each, and how many bytes a slot holds. These are the boards' numbers
// (firmware/boards/*: stm32f405 memory_map.hpp, sim sim_flash_layout()); the Linux board
// and the simulated one run an image from either slot, load_address 0.
struct SlotLayout {
  std::array<uint32_t, 2> base{};
  uint32_t capacity = 0;  // bytes; 0 = no limit the host knows of
};
std::optional<SlotLayout> slot_layout(protocol::HwModel model);

// The image of `images` this board takes next (SPEC.md §7.2). kImageRejected when none fits,
// saying for each image why ("fw.bin: built for stm32f405 rev 2..3, board is rev 1").
// The result points into `images`, which must outlive it (hence no temporaries).
HostResult<const FirmwareImage*> choose_image(const std::vector<FirmwareImage>& images, const protocol::Info& board,
                                              const std::string& board_name);
HostResult<const FirmwareImage*> choose_image(std::vector<FirmwareImage>&& images, const protocol::Info& board,
                                              const std::string& board_name) = delete;

// "stm32f405", "linux", "sim".
const char* hw_model_name(protocol::HwModel model);

}  // namespace tetrapulse::host
