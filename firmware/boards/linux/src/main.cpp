// tetrapulse-board: a Linux computer as a tetrapulse target board (linux_board.hpp).
//
//   tetrapulse-board --flash FILE [--factory-image IMG] [--node N] [--serial HEX]
//                    [--can IFACE] [--led LINE]... [--sync-line LINE]
//                    [--usb-gadget NAME [--usb-mount DIR] [--udc UDC]] ...
//   tetrapulse-board image --fw-version X.Y.Z (--payload FILE | --payload-size N) --out IMG
//
// A reset re-executes the program with the same arguments (plus --stay-in-bootloader when
// the reset asks the bootloader to stay), so each boot starts from the flash file.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tetrapulse/linux_board/board_image.hpp"
#include "tetrapulse/linux_board/linux_board.hpp"

namespace {

namespace lb = tetrapulse::linux_board;

struct ImageArgs {
  std::string version;
  std::string payload;
  size_t payload_size = 0;
  uint32_t seed = 1;
  std::string out;
};

int write_image(const ImageArgs& a) {
  const std::optional<uint32_t> version = lb::parse_version(a.version);
  if (!version) {
    std::fprintf(stderr, "tetrapulse-board image: --fw-version '%s' is not MAJOR.MINOR.PATCH\n", a.version.c_str());
    return 2;
  }
  std::vector<uint8_t> payload;
  if (!a.payload.empty()) {
    std::ifstream in(a.payload, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "tetrapulse-board image: %s: cannot read\n", a.payload.c_str());
      return 1;
    }
    payload.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } else {
    payload = lb::seeded_payload(a.payload_size, a.seed);
  }
  const std::vector<uint8_t> image = lb::make_linux_image(*version, payload);
  if (image.empty()) {
    std::fprintf(stderr, "tetrapulse-board image: the payload is empty\n");
    return 2;
  }
  std::ofstream out(a.out, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(image.data()), static_cast<std::streamsize>(image.size()));
  if (!out) {
    std::fprintf(stderr, "tetrapulse-board image: %s: cannot write\n", a.out.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"A Linux computer as a tetrapulse target board"};
  app.require_subcommand(0, 1);
  lb::LinuxBoardOptions o;
  std::string serial;
  int node = 1;
  app.add_option("--flash", o.flash_path, "Flash file (created erased, with the factory image, when missing)")
      ->capture_default_str();
  app.add_option("--factory-image", o.factory_image, "Image programmed into slot 0 of a new flash file")
      ->check(CLI::ExistingFile);
  app.add_option("--node", node, "CAN node id of a new flash file's configuration")->check(CLI::Range(1, 254));
  app.add_option("--serial", serial, "Unique id, 24 hex digits (default: from /etc/machine-id)");
  app.add_option("--can", o.can_interface, "SocketCAN interface");
  app.add_option("--led", o.led_lines, "GPIO line of marker 0, 1, 2, 3 in turn (CHIP:LINE or a line name)");
  app.add_option("--sync-line", o.sync_line, "GPIO sync input line (CHIP:LINE or a line name)");
  app.add_option("--usb-gadget", o.usb_gadget, "configfs gadget name for the USB device side (FunctionFS)");
  app.add_option("--usb-mount", o.usb_mount, "FunctionFS mount point (default /dev/ffs-<gadget>)");
  app.add_option("--udc", o.usb_udc, "USB device controller (default: the first in /sys/class/udc)");
  app.add_option("--clock-ppm", o.clock_ppm, "Rate error of the local clock against CLOCK_MONOTONIC (tests)")
      ->check(CLI::Range(-1000.0, 1000.0));
  app.add_flag("--report-clock", o.report_clock, "Print the board's rig time for a monotonic instant every second");
  app.add_option("--dfu-idle-s", o.dfu_idle_s, "DFU mode returns to a valid application after this long idle")
      ->check(CLI::Range(1, 3600))
      ->capture_default_str();
  app.add_flag("--stay-in-bootloader", o.stay_in_bootloader, "Start in DFU mode (set by a reset that asks for it)");

  ImageArgs image;
  CLI::App* make = app.add_subcommand("image", "Write a firmware image for this board");
  make->add_option("--fw-version", image.version, "Version MAJOR.MINOR.PATCH")->required();
  auto* payload = make->add_option("--payload", image.payload, "Payload file")->check(CLI::ExistingFile);
  make->add_option("--payload-size", image.payload_size, "Or: this many seeded bytes")
      ->check(CLI::Range(1, 0x40000 - 128))
      ->excludes(payload);
  make->add_option("--seed", image.seed, "Seed of the seeded payload");
  make->add_option("--out", image.out, "Image file to write")->required();
  CLI11_PARSE(app, argc, argv);
  if (make->parsed()) return write_image(image);

  o.node_id = static_cast<uint8_t>(node);
  if (serial.empty()) {
    o.serial = lb::machine_serial();
  } else if (const auto parsed = lb::parse_serial(serial)) {
    o.serial = *parsed;
  } else {
    std::fprintf(stderr, "tetrapulse-board: --serial '%s' is not 24 hex digits\n", serial.c_str());
    return 2;
  }
  if (o.usb_mount.empty() && !o.usb_gadget.empty()) o.usb_mount = "/dev/ffs-" + o.usb_gadget;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  const lb::BoardResult<tetrapulse::protocol::RebootMode> reset = lb::run_board(o);
  if (!reset) {
    lb::board_log("error: " + reset.error().what());
    return 1;
  }
  // A reset: the same program and arguments again, asking the bootloader to stay or not.
  std::vector<std::string> args;
  for (int i = 0; i < argc; ++i) {
    if (std::string(argv[i]) != "--stay-in-bootloader") args.emplace_back(argv[i]);
  }
  if (*reset == tetrapulse::protocol::RebootMode::kBootloader) args.emplace_back("--stay-in-bootloader");
  std::vector<char*> c_args;
  for (std::string& a : args) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  ::execv("/proc/self/exe", c_args.data());
  std::perror("tetrapulse-board: cannot restart (execv /proc/self/exe)");
  return 1;
}
