#include "tetrapulse/linux_board/linux_board.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>

#include "board_boot.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/linux_board/monotonic_clock.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace tp = protocol;

// A new flash file gets what a factory programs: the image in slot 0 (confirmed) and a
// configuration carrying the node id.
BoardResult<void> program_factory(const LinuxBoardOptions& o, FileFlash& flash) {
  const auto flash_error = [&](std::string message) {
    return board_error(BoardErrorKind::kFlash, flash.path(), std::move(message));
  };
  const auto image_error = [&](std::string message) {
    return board_error(BoardErrorKind::kFactoryImage, o.factory_image, std::move(message));
  };
  const fw::FlashLayout layout = linux_flash_layout();
  fw::RecordStore store(flash, layout.record_sectors);
  if (!store.open()) return flash_error("cannot format the record store");
  tp::Config config = tp::default_config();
  config.node_id = o.node_id;
  if (!fw::save_config(store, config)) return flash_error("cannot store the factory configuration");
  if (o.factory_image.empty()) return {};
  std::ifstream in(o.factory_image, std::ios::binary);
  const std::vector<uint8_t> image{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in.good() && !in.eof()) return image_error("cannot read");
  const tp::ByteView bytes{image.data(), image.size()};
  const tp::Result<tp::ImageHeader> header = tp::decode_image_header(bytes);
  if (!header) return image_error(std::string("not a firmware image (") + tp::error_name(header.error()) + ")");
  if (!tp::fits(*header, tp::HwModel::kLinuxBoard, LinuxSystem::kHwRevision) || !tp::check_payload(*header, bytes) ||
      image.size() > layout.slots[0].region.size) {
    return image_error("not a valid image for this board (model, revision, payload CRC or size)");
  }
  if (!flash.load(layout.slots[0].region.address, bytes)) return flash_error("cannot program slot 0");
  fw::BootState state;
  state.confirmed_slot = 0;
  if (!fw::save_boot_state(store, state)) return flash_error("cannot store the boot state");
  return {};
}

}  // namespace

void board_log(const std::string& line) {
  const int64_t now = monotonic_ns();
  std::printf("tetrapulse-board: [%lld.%03lld] %s\n", static_cast<long long>(now / 1'000'000'000),
              static_cast<long long>(now / 1'000'000 % 1000), line.c_str());
  std::fflush(stdout);
}

tp::UsbDeviceParams linux_usb_params(tp::UsbMode mode, uint32_t fw_version) {
  tp::UsbDeviceParams p;
  p.mode = mode;
  p.bcd_device = static_cast<uint16_t>((tp::version_major(fw_version) << 8) | tp::version_minor(fw_version));
  // The UDC renumbers endpoints anyway; distinct numbers keep FunctionFS's map simple.
  p.bulk_out_address = 0x01;
  p.bulk_in_address = 0x82;
  return p;
}

BoardResult<std::unique_ptr<FfsFunction>> open_usb_function(UsbGadget& gadget, const LinuxBoardOptions& o,
                                                             const tp::UsbDeviceParams& params) {
  const UsbGadgetSpec spec{o.usb_gadget, o.usb_mount, params.mode, params.bcd_device, serial_text(o.serial), o.usb_udc};
  if (BoardResult<void> made = gadget.create(spec); !made) return tl::unexpected(made.error());
  BoardResult<std::unique_ptr<FfsFunction>> usb = FfsFunction::open(o.usb_mount, params, serial_text(o.serial));
  if (!usb) gadget.remove();
  return usb;
}

BoardResult<tp::RebootMode> run_board(const LinuxBoardOptions& o) {
  BoardResult<std::unique_ptr<FileFlash>> opened = FileFlash::open(o.flash_path, linux_flash_sectors());
  if (!opened) return tl::unexpected(opened.error());
  FileFlash& flash = **opened;
  if (flash.created()) {
    if (BoardResult<void> programmed = program_factory(o, flash); !programmed) {
      std::remove(o.flash_path.c_str());  // the next start tries the factory again
      return tl::unexpected(programmed.error());
    }
    board_log("new flash " + o.flash_path + (o.factory_image.empty() ? " (no image)" : " with " + o.factory_image));
  }
  const fw::BoardModel model{tp::HwModel::kLinuxBoard, LinuxSystem::kHwRevision};
  const fw::BootChoice choice = fw::choose_boot_slot(flash, linux_flash_layout(), model, o.stay_in_bootloader);
  if (!choice.boot) return run_dfu_mode(o, flash);
  return run_application(o, flash, choice);
}

}  // namespace tetrapulse::linux_board
