// One boot of the application: the firmware core on the Linux board's seams, in a single
// thread that waits on every source at once (ppoll) and wakes for the next LED change.
#include <poll.h>
#include <signal.h>

#include <cinttypes>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "board_boot.hpp"
#include "tetrapulse/fw/app/firmware.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/fw/usb/usb_message_function.hpp"
#include "tetrapulse/linux_board/ffs_function.hpp"
#include "tetrapulse/linux_board/gpio_leds.hpp"
#include "tetrapulse/linux_board/gpio_sync_input.hpp"
#include "tetrapulse/linux_board/monotonic_clock.hpp"
#include "tetrapulse/linux_board/socketcan_bus.hpp"
#include "tetrapulse/linux_board/usb_gadget.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace tp = protocol;

constexpr int64_t kPollPeriodNs = 2'000'000;  // the main loop runs at least this often

std::string version_text(uint32_t v) {
  return std::to_string(tp::version_major(v)) + "." + std::to_string(tp::version_minor(v)) + "." +
         std::to_string(tp::version_patch(v));
}

const char* sync_state_name(tp::SyncState s) {
  switch (s) {
    case tp::SyncState::kFreeRunning: return "free-running";
    case tp::SyncState::kAcquiring: return "acquiring";
    case tp::SyncState::kLocked: return "locked";
    case tp::SyncState::kHoldover: return "holdover";
  }
  return "unknown";
}

}  // namespace

BoardResult<tp::RebootMode> run_application(const LinuxBoardOptions& o, FileFlash& flash, const fw::BootChoice& choice) {
  MonotonicClock clock(o.clock_ppm);
  LinuxSystem system(o.serial);
  BoardResult<std::unique_ptr<GpioLeds>> opened_leds = GpioLeds::open(clock, o.led_lines);
  if (!opened_leds) return tl::unexpected(opened_leds.error());
  GpioLeds& leds = **opened_leds;
  std::unique_ptr<GpioSyncInput> sync_input;
  if (!o.sync_line.empty()) {
    BoardResult<std::unique_ptr<GpioSyncInput>> opened = GpioSyncInput::open(clock, o.sync_line);
    if (!opened) return tl::unexpected(opened.error());
    sync_input = std::move(*opened);
  }
  std::unique_ptr<SocketCanBus> can_bus;
  std::optional<fw::CanLink> can_link;
  if (!o.can_interface.empty()) {
    BoardResult<std::unique_ptr<SocketCanBus>> opened = SocketCanBus::open(o.can_interface, clock);
    if (!opened) return tl::unexpected(opened.error());
    can_bus = std::move(*opened);
    can_link.emplace(*can_bus, MonotonicClock::kTickHz, o.node_id);
  }

  fw::FirmwareParts parts;
  parts.clock = &clock;
  parts.leds = &leds;
  parts.flash = &flash;
  parts.system = &system;
  parts.sync_input = sync_input.get();
  parts.can = can_link ? &*can_link : nullptr;
  parts.layout = linux_flash_layout();
  parts.board.fw_version = choice.header.fw_version;
  parts.board.active_slot = choice.slot;
  // One bit needs two line changes the main loop wakes for: 1 ms bits at the shortest.
  parts.board.min_bit_period_ns = 1'000'000;
  parts.board.capabilities = tp::capability::kCanUpdate;
  if (can_link) parts.board.capabilities |= tp::capability::kCan;
  if (sync_input) parts.board.capabilities |= tp::capability::kGpioSyncInput;
  if (!o.usb_gadget.empty()) parts.board.capabilities |= tp::capability::kUsb | tp::capability::kDfu;
  fw::Firmware firmware(parts);
  firmware.start();  // sets the CAN node from the stored configuration

  // USB: the message interface and the DFU run-time interface.
  UsbGadget gadget;
  std::unique_ptr<FfsFunction> usb;
  std::optional<fw::UsbLink> usb_link;
  std::optional<fw::UsbMessageFunction> messages;
  std::optional<fw::DfuDevice> dfu;
  const tp::UsbDeviceParams params = linux_usb_params(tp::UsbMode::kApplication, choice.header.fw_version);
  if (!o.usb_gadget.empty()) {
    BoardResult<std::unique_ptr<FfsFunction>> opened = open_usb_function(gadget, o, params);
    if (!opened) return tl::unexpected(opened.error());
    usb = std::move(*opened);
    usb_link.emplace(*usb);
    firmware.board().set_message_links(nullptr, &*usb_link);
    messages.emplace(*usb_link, firmware, clock,
                     tp::kUsbCapabilityBulkMessages | tp::kUsbCapabilityControlMessages | tp::kUsbCapabilityDfuRuntime);
    dfu.emplace(static_cast<fw::DfuRuntimeTarget&>(system), params);
    usb->set_function(tp::kUsbMessageInterface, *messages);
    usb->set_function(tp::kUsbDfuRuntimeInterface, *dfu);
    if (BoardResult<void> bound = gadget.bind(); !bound) return tl::unexpected(bound.error());
  }
  board_log("application " + version_text(choice.header.fw_version) + " from slot " + std::to_string(choice.slot) +
            ", node " + std::to_string(firmware.board().config().node_id) +
            (usb ? ", USB serial " + serial_text(o.serial) : std::string()) + (can_bus ? ", CAN " + o.can_interface : "") +
            (sync_input ? ", sync input " + o.sync_line : "") + ", " + std::to_string(o.led_lines.size()) + " LED lines");

  int64_t next_report = monotonic_ns() + 1'000'000'000;
  bool confirmed = firmware.confirmed();
  for (;;) {
    std::vector<pollfd> fds;
    const int ep0 = usb ? usb->ep0_fd() : -1;
    const int bulk = usb ? usb->bulk_fd() : -1;
    const int can_fd = can_bus ? can_bus->fd() : -1;
    const int sync_fd = sync_input ? sync_input->fd() : -1;
    for (int fd : {ep0, bulk, can_fd, sync_fd}) {
      if (fd >= 0) fds.push_back({fd, POLLIN, 0});
    }
    const int64_t now = monotonic_ns();
    int64_t wake = now + kPollPeriodNs;
    if (const std::optional<fw::Tick> due = leds.next_due()) {
      const int64_t at = clock.to_monotonic(*due);
      if (at < wake) wake = at;
    }
    const int64_t wait = wake > now ? wake - now : 0;
    const timespec timeout{static_cast<time_t>(wait / 1'000'000'000), static_cast<long>(wait % 1'000'000'000)};
    const int ready = ::ppoll(fds.data(), fds.size(), &timeout, nullptr);
    if (ready > 0) {
      for (const pollfd& p : fds) {
        if ((p.revents & (POLLIN | POLLERR | POLLHUP)) == 0) continue;
        if (p.fd == ep0) {
          for (const char* event : usb->handle_ep0()) board_log(std::string("usb: ") + event);
        } else if (p.fd == bulk) {
          for (const BulkTransfer& t : usb->take_bulk()) {
            usb_link->on_bulk_transfer(tp::ByteView{t.bytes.data(), t.bytes.size()}, clock.at(t.monotonic_ns), firmware);
          }
        } else if (p.fd == can_fd) {
          while (const std::optional<ReceivedCanFrame> f = can_bus->receive()) {
            can_link->on_frame(f->frame, f->rx, firmware);
          }
        } else if (p.fd == sync_fd) {
          for (const fw::Tick t : sync_input->read_edges()) firmware.on_sync_edge(t);
        }
      }
    }
    leds.apply_due(clock.now());
    firmware.poll();
    if (dfu) dfu->poll(static_cast<uint32_t>(monotonic_ns() / 1'000'000));
    if (!confirmed && firmware.confirmed()) {
      confirmed = true;
      board_log("image " + version_text(choice.header.fw_version) + " in slot " + std::to_string(choice.slot) +
                " confirmed");
    }
    if (const auto& mode = system.requested()) {
      if (usb) usb->drain(500);  // the reboot's Ack leaves first
      board_log(std::string("reset") + (*mode == tp::RebootMode::kBootloader ? " into the DFU bootloader" : ""));
      return *mode;
    }
    if (o.report_clock && monotonic_ns() >= next_report) {
      next_report += 1'000'000'000;
      // The board's rig time for one monotonic instant: with the host's rig time being
      // CLOCK_MONOTONIC + offset on the same machine, rig_ns - monotonic_ns - offset is the
      // board's true error.
      const int64_t m = monotonic_ns();
      const fw::Tick t = clock.at(m);
      const tp::StatusReport s = firmware.board().status(t);
      char line[256];
      std::snprintf(line, sizeof(line),
                    "clock monotonic_ns %" PRId64 " rig_ns %" PRId64 " sync %s offset_ns %d rate_ppb %d accepted %u"
                    " held %u led_changes %" PRIu64 " led_late_ns %" PRId64 " led_late_max_ns %" PRId64,
                    m, firmware.board().sync().servo().to_rig(t), sync_state_name(s.sync_state), s.offset_ns,
                    s.rate_ppb, s.sync_accepted, firmware.board().sync().servo().held_out(), leds.lateness().applied, leds.lateness().last_ns,
                    leds.lateness().max_ns);
      board_log(line);
    }
  }
}

}  // namespace tetrapulse::linux_board
