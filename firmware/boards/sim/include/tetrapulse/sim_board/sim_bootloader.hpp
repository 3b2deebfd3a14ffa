#pragma once
// The simulated board's bootloader while it waits for an update, built from the core as
// bootloader/stm32f405/main.cpp builds it: the slot survey, then two paths into the slot
// that is not the known-good image,
//   CAN  CanLink -> BootloaderCommandHandler -> UpdateReceiver (UpdateBegin/Chunk/Verify,
//        GetInfo, GetStatus, Reboot), at the node id of the stored configuration;
//   DFU  DfuDevice (DFU mode, interface 0) -> ImageBundleWriter; once the host has the
//        verdict of an installed image the board restarts into it (kRestartAfterInstallMs).
// SimBoard owns one while no application runs; the host reaches the DFU interface as a
// FunctionFS gadget hands it over (whole control stages into one UsbFunction).
#include <cstdint>
#include <optional>

#include "tetrapulse/fw/boot/bootloader_command_handler.hpp"
#include "tetrapulse/fw/boot/image_bundle_writer.hpp"
#include "tetrapulse/fw/boot/slot_survey.hpp"
#include "tetrapulse/fw/boot/update_receiver.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"

namespace tetrapulse::sim_board {

class SimBootloader {
 public:
  static constexpr uint32_t kRestartAfterInstallMs = 100;  // as the STM32F405's
  static constexpr uint16_t kTransferSize = 1024;

  SimBootloader(fw::Flash& flash, const fw::FlashLayout& layout, const fw::BoardModel& board, fw::CanBus& can,
                const fw::LocalClock& clock, fw::BootloaderIdentity identity);
  SimBootloader(const SimBootloader&) = delete;
  SimBootloader& operator=(const SimBootloader&) = delete;

  fw::CanLink& can_link() { return can_link_; }
  fw::BootloaderCommandHandler& commands() { return commands_; }
  fw::DfuDevice& dfu() { return dfu_; }
  uint8_t target_slot() const { return target_; }

  // The main loop at `now_ms`: DFU work; the reset it asks for, if any (Reboot over CAN,
  // or an installed DFU download kRestartAfterInstallMs after its verdict).
  std::optional<protocol::RebootMode> poll(uint32_t now_ms);

 private:
  fw::RecordStore store_;
  fw::SlotSurvey survey_;
  uint8_t target_;
  fw::CanLink can_link_;
  fw::UpdateReceiver update_;
  fw::BootloaderCommandHandler commands_;
  fw::ImageBundleWriter writer_;
  uint8_t block_[kTransferSize] = {};
  fw::DfuDevice dfu_;
  std::optional<uint32_t> installed_at_ms_;
};

// What the bootloader tells the host about itself (SPEC.md §7.3).
fw::BootloaderIdentity sim_bootloader_identity(const fw::BoardModel& board, uint8_t node_id);

}  // namespace tetrapulse::sim_board
