// `tetrapulse flash`: install firmware on a board. Of the images given (a release has one
// per slot) the board gets the one built for its model and revision and linked for its
// inactive slot. USB boards with a DFU bootloader get it by USB DFU (as dfu-util does);
// every other link uses the protocol's update messages (SPEC.md §7.3). Either way the
// board is restarted and must then report the image's version.
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"
#include "stop_signal.hpp"
#include "tetrapulse/host/firmware_update.hpp"
#include "tetrapulse/host/usb_dfu.hpp"
#include "tetrapulse/host/usb_discovery.hpp"
#include "tetrapulse/host/usb_link.hpp"

namespace tetrapulse::cli {
namespace {

using host::FirmwareImage;
using host::HostError;
using host::HostErrorKind;

struct FlashArgs {
  BoardOptions board;
  std::vector<std::string> images;
  std::string method = "auto";
  bool no_reboot = false;
  size_t chunk_size = 256;
  size_t transfer_size = 1024;
  int reconnect_ms = 15000;
};

// Progress on stderr: a bar on a terminal, one line per stage otherwise; JSON lines with --json.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool json) : json_(json), tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(const host::FlashProgress& p) {
    if (json_) {
      fmt::print("{}\n", JsonObject().str("stage", p.stage).num("done", p.done).num("total", p.total).text());
      std::fflush(stdout);
      return;
    }
    const bool new_stage = stage_ != p.stage;
    if (new_stage && tty_ && !stage_.empty()) std::fputc('\n', stderr);
    stage_ = p.stage;
    if (tty_) {
      const int width = 30;
      const int filled = p.total == 0 ? width : static_cast<int>(width * p.done / p.total);
      std::fprintf(stderr, "\r%-9s [%s%s] %3d%%", p.stage, std::string(static_cast<size_t>(filled), '#').c_str(),
                   std::string(static_cast<size_t>(width - filled), ' ').c_str(),
                   p.total == 0 ? 100 : static_cast<int>(100 * p.done / p.total));
    } else if (new_stage) {
      std::fprintf(stderr, "tetrapulse flash: %s\n", p.stage);
    }
  }
  void finish() {
    if (tty_ && !stage_.empty() && !json_) std::fputc('\n', stderr);
  }

 private:
  bool json_;
  bool tty_;
  std::string stage_;
};

int done(const FlashArgs& a, const std::string& address, const FirmwareImage& image, const char* method,
         uint32_t running) {
  if (a.board.json) {
    JsonObject o;
    o.str("address", address).str("image", image.name).str("method", method).str("version", version_text(image.header.fw_version));
    o.flag("rebooted", !a.no_reboot);
    if (!a.no_reboot) o.str("running_version", version_text(running));
    fmt::print("{}\n", o.text());
  } else {
    fmt::print("{}: {} written by {}{}\n", address, image.name, method,
               a.no_reboot ? " (not restarted)" : fmt::format(", now running {}", version_text(running)));
  }
  return kExitOk;
}

int flash_by_protocol(const FlashArgs& a, host::Board& board, const protocol::Info& info,
                      const std::vector<FirmwareImage>& images, ProgressPrinter& progress) {
  auto chosen = host::choose_image(images, info, board.name());
  if (!chosen) return report_failure("flash", chosen.error());
  host::UpdateOptions o;
  o.chunk_size = a.chunk_size;
  o.reboot = !a.no_reboot;
  o.progress = [&](const host::FlashProgress& p) { progress(p); };
  o.cancel = &stop_on_signals();
  auto report = host::update_firmware(board, **chosen, o);
  progress.finish();
  if (!report) return report_failure("flash", report.error());
  return done(a, board.name(), **chosen, "update messages", report->running_version);
}

int flash_by_protocol(const FlashArgs& a, const std::vector<FirmwareImage>& images, ProgressPrinter& progress) {
  auto board = open_board(a.board);
  if (!board) return report_failure("flash", board.error());
  auto info = (*board)->info();
  if (!info) return report_failure("flash", info.error());
  return flash_by_protocol(a, **board, *info, images, progress);
}

int flash_by_dfu(const FlashArgs& a, const std::string& serial_given, const std::vector<FirmwareImage>& images,
                 ProgressPrinter& progress) {
  const FirmwareImage* chosen = nullptr;
  std::string serial = serial_given;
  auto link = host::UsbLink::open(serial_given);
  if (link) {
    serial = (*link)->serial();
    host::Board board(std::move(*link));
    auto info = board.info();
    if (!info) return report_failure("flash", info.error());
    if (a.method == "auto" && (info->capabilities & protocol::capability::kDfu) == 0) {
      return flash_by_protocol(a, board, *info, images, progress);  // no DFU bootloader
    }
    auto fits = host::choose_image(images, *info, board.name());
    if (!fits) return report_failure("flash", fits.error());
    chosen = *fits;
  } else if (link.error().kind == HostErrorKind::kNotFound && images.size() == 1) {
    chosen = &images.front();  // already in its bootloader (or not a board at all: DFU finds out)
  } else if (link.error().kind == HostErrorKind::kNotFound) {
    return report_failure("flash", HostError{HostErrorKind::kBadInput, host::usb_link_name(serial_given),
                                             "not running its application, so its slot is unknown: give the one "
                                             "image for the slot its bootloader writes"});
  } else {
    return report_failure("flash", link.error());
  }
  host::UsbDfuOptions o;
  o.transfer_size = a.transfer_size;
  o.reset_after = !a.no_reboot;
  o.progress = [&](const host::FlashProgress& p) { progress(p); };
  o.cancel = &stop_on_signals();
  auto report = host::usb_dfu_flash(serial, protocol::ByteView{chosen->bytes.data(), chosen->bytes.size()}, o);
  if (!report) {
    progress.finish();
    return report_failure("flash", report.error());
  }
  const std::string address = host::usb_link_name(report->serial);
  if (a.no_reboot) {
    progress.finish();
    return done(a, address, *chosen, "USB DFU", 0);
  }
  progress(host::FlashProgress{"reconnect", 0, 1});
  auto back = host::UsbLink::wait_and_open(report->serial, std::chrono::milliseconds(a.reconnect_ms));
  if (!back) {
    progress.finish();
    return report_failure("flash", back.error());
  }
  host::Board board(std::move(*back));
  auto info = board.info();
  progress(host::FlashProgress{"reconnect", 1, 1});
  progress.finish();
  if (!info) return report_failure("flash", info.error());
  if (info->fw_version != chosen->header.fw_version) {
    return report_failure("flash", HostError{HostErrorKind::kVerifyFailed, address,
                                             fmt::format("after the download the board runs {}, not the image's {}",
                                                         version_text(info->fw_version),
                                                         version_text(chosen->header.fw_version))});
  }
  return done(a, address, *chosen, "USB DFU", info->fw_version);
}

int run_flash(const FlashArgs& a) {
  std::vector<FirmwareImage> images;
  for (const std::string& path : a.images) {
    auto image = host::read_firmware_image(path);
    if (!image) return report_failure("flash", image.error());
    images.push_back(std::move(*image));
  }
  auto address = board_address(a.board);
  if (!address) return report_failure("flash", address.error());
  if (a.method == "dfu" && address->kind != host::BoardAddress::Kind::kUsb) {
    return report_failure("flash", HostError{HostErrorKind::kBadInput, address->text(), "--method dfu needs a USB board"});
  }
  ProgressPrinter progress(a.board.json);
  const bool dfu = address->kind == host::BoardAddress::Kind::kUsb && a.method != "protocol";
  return dfu ? flash_by_dfu(a, address->usb_serial, images, progress) : flash_by_protocol(a, images, progress);
}

}  // namespace

void add_flash_command(CLI::App& app, int* result) {
  auto a = std::make_shared<FlashArgs>();
  auto* cmd = app.add_subcommand("flash", "Install firmware on a board (USB DFU or the update messages), then restart it");
  add_board_options(cmd, &a->board);
  cmd->add_option("image", a->images, "Firmware image files (TPFW header); a release's per-slot images")
      ->required();
  cmd->add_option("--method", a->method,
                  "auto: USB DFU for USB boards whose bootloader has it, update messages otherwise; dfu; protocol")
      ->check(CLI::IsMember({"auto", "dfu", "protocol"}))
      ->capture_default_str();
  cmd->add_flag("--no-reboot", a->no_reboot, "Leave the new image verified but not started");
  cmd->add_option("--chunk-size", a->chunk_size, "Bytes per UpdateChunk")->check(CLI::Range(1, 256))->capture_default_str();
  cmd->add_option("--transfer-size", a->transfer_size,
                  "DFU bytes per DNLOAD when the device does not say (no DFU functional descriptor)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  cmd->add_option("--reconnect-ms", a->reconnect_ms, "How long a USB board may take to come back after the download")
      ->check(CLI::Range(100, 600000))
      ->capture_default_str();
  cmd->callback([a, result] { *result = run_flash(*a); });
}

}  // namespace tetrapulse::cli
