// One boot of the bootloader: the DFU-mode gadget (PID 0x0002) writing a download into the
// slot that is not the known-good one (ImageBundleWriter: header, fits, payload CRC-32C,
// then the slot is marked pending). After an installed download the board resets into
// it; after a refused one, or a host that went away, it stays in DFU mode until the host
// is idle for options.dfu_idle_s and then returns to the known-good application.
#include <poll.h>

#include <array>

#include "board_boot.hpp"
#include "tetrapulse/fw/boot/image_bundle_writer.hpp"
#include "tetrapulse/fw/boot/slot_survey.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/linux_board/ffs_function.hpp"
#include "tetrapulse/linux_board/monotonic_clock.hpp"
#include "tetrapulse/linux_board/usb_gadget.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace tp = protocol;

// After the verdict the board waits this long for the host's USB reset, then restarts
// into the new image anyway; after the reset it lets the host's reset call return first.
constexpr int64_t kResetGraceNs = 3'000'000'000;
constexpr int64_t kAfterResetNs = 500'000'000;

const char* status_name(tp::DfuStatusCode s) {
  switch (s) {
    case tp::DfuStatusCode::kOk: return "OK";
    case tp::DfuStatusCode::kErrTarget: return "errTARGET (image not for this board)";
    case tp::DfuStatusCode::kErrFile: return "errFILE (not a firmware image)";
    case tp::DfuStatusCode::kErrAddress: return "errADDRESS (image does not fit the slot)";
    case tp::DfuStatusCode::kErrNotDone: return "errNOTDONE (download ended mid-image)";
    case tp::DfuStatusCode::kErrVerify: return "errVERIFY (payload CRC-32C or checks failed)";
    case tp::DfuStatusCode::kErrStalledPacket: return "errSTALLEDPKT (request refused)";
    default: return "error";
  }
}

}  // namespace

BoardResult<tp::RebootMode> run_dfu_mode(const LinuxBoardOptions& o, FileFlash& flash) {
  const fw::FlashLayout layout = linux_flash_layout();
  const fw::BoardModel model{tp::HwModel::kLinuxBoard, LinuxSystem::kHwRevision};
  fw::RecordStore store(flash, layout.record_sectors);
  const fw::SlotSurvey survey = fw::survey_slots(store, flash, layout, model);
  const uint8_t good = survey.known_good();
  const uint8_t target = survey.update_target();

  if (o.usb_gadget.empty()) {
    if (good != fw::kNoSlot) {
      board_log("bootloader: no USB gadget to update through; starting the application");
      return tp::RebootMode::kApplication;
    }
    return board_error(BoardErrorKind::kNoImage, "",
                       "no valid image in either slot and no USB gadget (--usb-gadget) to receive one");
  }
  fw::ImageBundleWriter writer(flash, layout, store, model, target, good);
  const tp::UsbDeviceParams params = linux_usb_params(tp::UsbMode::kBootloader, 0);
  std::array<uint8_t, 4096> block{};
  fw::DfuDevice dfu(writer, params, block.data(), block.size());

  UsbGadget gadget;
  BoardResult<std::unique_ptr<FfsFunction>> opened = open_usb_function(gadget, o, params);
  if (!opened) return tl::unexpected(opened.error());
  FfsFunction& usb = **opened;
  usb.set_function(0, dfu);
  if (BoardResult<void> bound = gadget.bind(); !bound) return tl::unexpected(bound.error());
  board_log("bootloader: DFU mode, writing slot " + std::to_string(target) +
            (good == fw::kNoSlot ? ", no valid application" : ", application in slot " + std::to_string(good)));

  int64_t idle_since = monotonic_ns();
  int64_t installed_at = 0;
  int64_t reset_done_at = 0;  // the host's USB reset after the verdict has re-enumerated the device
  tp::DfuStatusCode reported = tp::DfuStatusCode::kOk;
  for (;;) {
    pollfd p{usb.ep0_fd(), POLLIN, 0};
    if (::poll(&p, 1, 5) > 0) {
      for (const char* event : usb.handle_ep0()) {
        board_log(std::string("usb: ") + event);
        // The host's USB reset after the verdict (dfu-util -R): the device goes (DISABLE) and
        // comes back (ENABLE); restart once libusb_reset_device has seen it return.
        if (installed_at != 0 && std::string(event) == "ENABLE") reset_done_at = monotonic_ns();
      }
    }
    const int64_t now = monotonic_ns();
    dfu.poll(static_cast<uint32_t>(now / 1'000'000));
    if (usb.last_request_ns() > idle_since) idle_since = usb.last_request_ns();
    if (dfu.status() != reported) {
      reported = dfu.status();
      if (reported != tp::DfuStatusCode::kOk && installed_at == 0) board_log(std::string("bootloader: download refused: ") + status_name(reported));
    }
    if (dfu.installed() && installed_at == 0) {
      installed_at = now;
      board_log("bootloader: image installed in slot " + std::to_string(target) + ", starting it");
    }
    if (installed_at != 0 && ((reset_done_at != 0 && now - reset_done_at >= kAfterResetNs) ||
                              (reset_done_at == 0 && now - installed_at >= kResetGraceNs))) {
      return tp::RebootMode::kApplication;
    }
    const bool mid_download = dfu.state() != tp::DfuState::kDfuIdle && dfu.state() != tp::DfuState::kDfuError;
    if (installed_at == 0 && good != fw::kNoSlot && !mid_download && now - idle_since >= int64_t{o.dfu_idle_s} * 1'000'000'000) {
      board_log("bootloader: no DFU request for " + std::to_string(o.dfu_idle_s) + " s; back to the application");
      return tp::RebootMode::kApplication;
    }
  }
}

}  // namespace tetrapulse::linux_board
