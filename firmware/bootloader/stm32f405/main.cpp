// The bootloader of the STM32F405 reference board.
//
// At reset it lets the core's boot selection (fw/boot/boot_slot.hpp) check both slots, choose
// one, record the choice and start it; clocks stay at their reset values on that path.
// It stays instead when the application asked it to (boot handoff: Reboot{bootloader},
// DFU_DETACH) or no slot holds a valid image, and waits for an update on two paths, both
// into the slot that is not the known-good image (fw/boot/update_slot.hpp):
//   USB DFU  1209:0002, one DFU-mode interface (SPEC.md §5.6). dfu-util sends
//            tetrapulse.dfu, the bundle of both slot images, or a single image; the
//            ImageBundleWriter keeps the target slot's one, verifies it at manifestation
//            and marks it pending; once the host has read the verdict the board resets
//            and the boot selection starts the new image on trial.
//   CAN      UpdateBegin/Chunk/Verify/Abort through the core's UpdateReceiver, GetInfo,
//            GetStatus, Reboot (SPEC.md §7.3), at the node id of the stored configuration.
// QEMU models neither the OTG core nor bxCAN: under the emulator this mode runs without
// either (the QEMU test only exercises the boot path).
#include <cstdint>

#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/fw/boot/bootloader_command_handler.hpp"
#include "tetrapulse/fw/boot/image_bundle_writer.hpp"
#include "tetrapulse/fw/boot/slot_survey.hpp"
#include "tetrapulse/fw/boot/update_receiver.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"
#include "tetrapulse/stm32f405/board_identity.hpp"
#include "tetrapulse/stm32f405/boot_handoff.hpp"
#include "tetrapulse/stm32f405/bx_can.hpp"
#include "tetrapulse/stm32f405/clock_tree.hpp"
#include "tetrapulse/stm32f405/internal_flash.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"
#include "tetrapulse/stm32f405/system.hpp"
#include "tetrapulse/stm32f405/usb_otg_fs.hpp"
#include "tetrapulse/stm32f405/watchdog.hpp"

namespace {

namespace fw = tetrapulse::fw;
namespace tp = tetrapulse::protocol;
using namespace tetrapulse::stm32f405;

constexpr uint32_t kRestartAfterInstallMs = 100;  // the verdict has left; let the host's transfer end
constexpr uint32_t kCanDrainMs = 50;              // a Reboot's Ack leaves before the reset
constexpr uint16_t kTransferSize = 1024;          // usb_descriptors.hpp default, SPEC §5.6

// Takes (and clears) a Reboot{bootloader} / DFU_DETACH request from the application.
bool take_stay_request(BootHandoff& h) {
  if (!handoff_valid(h)) {
    h = BootHandoff{};
    h.booted_slot = fw::kNoSlot;
    seal_handoff(h);
    return false;
  }
  const bool stay = h.request == static_cast<uint32_t>(BootRequest::kStayInBootloader);
  h.request = static_cast<uint32_t>(BootRequest::kNone);
  seal_handoff(h);
  return stay;
}

[[noreturn]] void restart(bool stay) {
  BootHandoff& h = boot_handoff();
  if (!handoff_valid(h)) {
    h = BootHandoff{};
    h.booted_slot = fw::kNoSlot;
  }
  h.request = static_cast<uint32_t>(stay ? BootRequest::kStayInBootloader : BootRequest::kNone);
  seal_handoff(h);
  system_reset();
}

uint32_t now_ms(const LocalTimer& clock) { return static_cast<uint32_t>(clock.read() / (clock.tick_hz() / 1000u)); }

[[noreturn]] void wait_for_update(InternalFlash& flash, const fw::FlashLayout& layout, const fw::BoardModel& board) {
  const Clocks clocks = configure_clocks();
  LocalTimer& clock = local_timer();
  clock.start(clocks.apb1_timer_hz);
  const bool real_chip = clocks.source != ClockSource::kUnreadable;

  static fw::RecordStore store(flash, layout.record_sectors);
  const fw::SlotSurvey survey = fw::survey_slots(store, flash, layout, board);
  const uint8_t target = survey.update_target();
  const uint8_t fallback = survey.known_good();

  // CAN: the core's update receiver writes `target` (it writes the slot that is not "active").
  const bool can_up = bx_can().start(clocks.apb1_hz, BxCan::kDefaultBitrate, clock);
  static fw::CanLink can_link(bx_can(), clock.tick_hz(), fw::load_config(store).config.node_id);
  static fw::UpdateReceiver update(flash, layout, store, board, target == 0 ? 1 : 0);

  // USB DFU.
  const bool usb_possible = clocks.usb_clock_ok && real_chip;
  static char serial[25] = "000000000000000000000000";
  if (real_chip) unique_id_hex(serial);
  static tp::UsbDeviceParams usb_params = usb_device_params(tp::UsbMode::kBootloader, TETRAPULSE_FW_VERSION);
  usb_params.dfu_transfer_size = kTransferSize;
  static UsbOtgFs usb;
  static uint8_t usb_answers[fw::UsbControl::kMinBuffer];  // descriptors, strings, DFU status
  static fw::UsbControl usb_control(usb_params, serial, usb, usb_answers, sizeof(usb_answers));
  static fw::UsbEndpointZero usb_ep0(usb_control);
  static fw::ImageBundleWriter writer(flash, layout, store, board, target, fallback);
  static uint8_t block[kTransferSize];
  static fw::DfuDevice dfu(writer, usb_params, block, sizeof(block));
  usb_control.set_function(0, dfu);
  const bool usb_up = usb_possible && usb.start(usb_ep0, usb_control, nullptr, clock);

  fw::BootloaderIdentity identity;
  identity.hw_model = board.model;
  identity.hw_revision = board.revision;
  identity.bootloader_version = TETRAPULSE_FW_VERSION;
  if (real_chip) identity.serial = unique_id();
  identity.capabilities = (can_up ? tp::capability::kCan | tp::capability::kCanUpdate : 0) |
                          (usb_up ? tp::capability::kUsb | tp::capability::kDfu : 0);
  identity.node_id = can_link.node();
  static fw::BootloaderCommandHandler commands(update, identity, clock, can_up ? &can_link : nullptr);

  bool installed = false;
  uint32_t installed_at = 0;
  for (;;) {
    feed_watchdog();  // harmless when no watchdog runs; the application's stops at reset
    usb.poll();
    const uint32_t now = now_ms(clock);
    dfu.poll(now);
    ReceivedFrame frame;
    while (bx_can().receive(&frame)) can_link.on_frame(frame.frame, frame.rx, commands);

    if (dfu.installed() && !installed) {
      installed = true;
      installed_at = now;
    }
    if (installed && now - installed_at >= kRestartAfterInstallMs) {
      usb.disconnect();
      restart(false);  // the boot selection starts the pending slot
    }
    if (commands.reboot_requested()) {
      const uint32_t asked = now;
      while (!bx_can().tx_idle() && now_ms(clock) - asked < kCanDrainMs) {
      }
      usb.disconnect();
      restart(commands.reboot_mode() == tp::RebootMode::kBootloader);
    }
  }
}

}  // namespace

int main() {
  static InternalFlash flash;
  const fw::FlashLayout layout = flash_layout();
  const fw::BoardModel board{tp::HwModel::kStm32f405Reference, kHardwareRevision};

  BootHandoff& handoff = boot_handoff();
  const bool stay = take_stay_request(handoff);
  const fw::BootChoice choice = fw::choose_boot_slot(flash, layout, board, stay);
  if (choice.boot && choice.slot < fw::kSlotCount) {
    handoff.bootloader_version = TETRAPULSE_FW_VERSION;
    handoff.booted_slot = choice.slot;
    seal_handoff(handoff);
    start_image(layout.slots[choice.slot].load_address + choice.header.vector_offset);
  }
  wait_for_update(flash, layout, board);
}
