#include "tetrapulse/sim_board/sim_bootloader.hpp"

#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::sim_board {
namespace {

protocol::UsbDeviceParams dfu_params() {
  protocol::UsbDeviceParams p;
  p.mode = protocol::UsbMode::kBootloader;
  p.dfu_transfer_size = SimBootloader::kTransferSize;
  return p;
}

}  // namespace

fw::BootloaderIdentity sim_bootloader_identity(const fw::BoardModel& board, uint8_t node_id) {
  fw::BootloaderIdentity id;
  id.hw_model = board.model;
  id.hw_revision = board.revision;
  id.bootloader_version = protocol::pack_version(1, 0, 0);
  id.capabilities = protocol::capability::kCan | protocol::capability::kCanUpdate | protocol::capability::kUsb |
                    protocol::capability::kDfu;
  id.node_id = node_id;
  return id;
}

SimBootloader::SimBootloader(fw::Flash& flash, const fw::FlashLayout& layout, const fw::BoardModel& board,
                             fw::CanBus& can, const fw::LocalClock& clock, fw::BootloaderIdentity identity)
    : store_(flash, layout.record_sectors),
      survey_(fw::survey_slots(store_, flash, layout, board)),
      target_(survey_.update_target()),
      can_link_(can, clock.tick_hz(), fw::load_config(store_).config.node_id),
      // The receiver writes the slot that is not "active".
      update_(flash, layout, store_, board, target_ == 0 ? 1 : 0),
      commands_(update_, [&] {
        identity.node_id = can_link_.node();
        return identity;
      }(), clock, &can_link_),
      writer_(flash, layout, store_, board, target_, survey_.known_good()),
      dfu_(writer_, dfu_params(), block_, sizeof(block_)) {}

std::optional<protocol::RebootMode> SimBootloader::poll(uint32_t now_ms) {
  dfu_.poll(now_ms);
  if (dfu_.installed() && !installed_at_ms_) installed_at_ms_ = now_ms;
  if (installed_at_ms_ && now_ms - *installed_at_ms_ >= kRestartAfterInstallMs) {
    return protocol::RebootMode::kApplication;  // the boot selection starts the pending slot
  }
  if (commands_.reboot_requested()) return commands_.reboot_mode();
  return std::nullopt;
}

}  // namespace tetrapulse::sim_board
