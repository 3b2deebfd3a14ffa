#include "board_options.hpp"

#include <cstdio>

#include "exit_codes.hpp"
#include "tetrapulse/host/sim_board_link.hpp"

namespace tetrapulse::cli {

using host::HostError;
using host::HostErrorKind;

void add_board_options(CLI::App* cmd, BoardOptions* o) {
  cmd->add_option("--usb", o->usb, "USB serial number of the board")->group("Board");
  cmd->add_option("--can", o->can, "CAN interface and node, IFACE:NODE")->group("Board");
  cmd->add_option("--serial", o->serial, "Serial port, PATH[:BAUD]")->group("Board");
  cmd->add_option("--board", o->board, "usb:SERIAL, can:IFACE:NODE, serial:PATH[:BAUD] or sim:NODE")->group("Board");
  cmd->add_option("--timeout-ms", o->timeout_ms, "How long to wait for each answer")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str()
      ->group("Board");
  cmd->add_flag("--json", o->json, "Machine-readable output (JSON)");
  cmd->footer(kBoardAddressHelp);
}

host::HostResult<host::BoardAddress> board_address(const BoardOptions& o) {
  const int given = (o.usb ? 1 : 0) + (o.can ? 1 : 0) + (o.serial ? 1 : 0) + (o.board ? 1 : 0);
  if (given != 1) {
    return host::host_error(HostErrorKind::kBadInput, "",
                            given == 0 ? "say which board: --usb SERIAL, --can IFACE:NODE, --serial PATH or --board ADDRESS"
                                       : "give one board address, not several");
  }
  if (o.usb) return host::parse_usb_address(*o.usb);
  if (o.can) return host::parse_can_address(*o.can);
  if (o.serial) return host::parse_serial_address(*o.serial);
  return host::parse_board_address(*o.board);
}

host::HostResult<std::unique_ptr<host::Link>> open_any_link(const host::BoardAddress& address) {
  return address.kind == host::BoardAddress::Kind::kSim ? host::open_sim_link(address) : host::open_link(address);
}

host::HostResult<std::unique_ptr<host::Board>> open_board(const BoardOptions& o) {
  auto address = board_address(o);
  if (!address) return tl::unexpected(address.error());
  auto link = open_any_link(*address);
  if (!link) return tl::unexpected(link.error());
  host::BoardTimeouts timeouts;
  timeouts.request = std::chrono::milliseconds(o.timeout_ms);
  timeouts.flash = std::max(timeouts.flash, timeouts.request);
  return std::make_unique<host::Board>(std::move(*link), timeouts);
}

int exit_code_for(const HostError& e) {
  switch (e.kind) {
    case HostErrorKind::kBadInput: return kExitUsage;
    case HostErrorKind::kBadFile:
    case HostErrorKind::kImageRejected: return kExitBadInput;
    case HostErrorKind::kNotFound:
    case HostErrorKind::kOpenFailed: return kExitNoDevice;
    case HostErrorKind::kVerifyFailed: return kExitCheckFailed;
    case HostErrorKind::kCancelled: return kExitFailure;
    case HostErrorKind::kIo:
    case HostErrorKind::kDisconnected:
    case HostErrorKind::kTimeout:
    case HostErrorKind::kMalformed:
    case HostErrorKind::kBoardRefused:
    case HostErrorKind::kBusOff: return kExitDeviceError;
  }
  return kExitFailure;
}

int report_failure(const char* command, const HostError& e) {
  std::fprintf(stderr, "tetrapulse %s: %s\n", command, e.what().c_str());
  return exit_code_for(e);
}

}  // namespace tetrapulse::cli
