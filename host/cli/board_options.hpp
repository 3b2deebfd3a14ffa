#pragma once
// What every board command shares: how a board is addressed (--usb, --can, --serial,
// --board), --json, and how a HostError becomes one line on stderr and an exit code.
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/board_address.hpp"
#include "tetrapulse/host/host_error.hpp"

namespace tetrapulse::cli {

struct BoardOptions {
  std::optional<std::string> usb;
  std::optional<std::string> can;
  std::optional<std::string> serial;
  std::optional<std::string> board;
  bool json = false;
  int timeout_ms = 1000;
};

inline constexpr const char* kBoardAddressHelp =
    "A board is addressed by exactly one of:\n"
    "  --usb SERIAL          its USB serial number (tetrapulse list); --usb '' for the only board\n"
    "  --can IFACE:NODE      SocketCAN interface and node id 1..254, e.g. can0:3\n"
    "  --serial PATH[:BAUD]  a serial port, 115200 baud unless given, e.g. /dev/ttyUSB0:921600\n"
    "  --board ADDRESS       usb:SERIAL, can:IFACE:NODE, serial:PATH[:BAUD] or sim:NODE (a simulated\n"
    "                        board in this process, fresh at every run)";

// --usb, --can, --serial, --board, --timeout-ms and --json on `cmd`.
void add_board_options(CLI::App* cmd, BoardOptions* options);

// The one address given (kBadInput when none or several are).
host::HostResult<host::BoardAddress> board_address(const BoardOptions& options);
// Opens the addressed board (simulated boards included).
host::HostResult<std::unique_ptr<host::Board>> open_board(const BoardOptions& options);
host::HostResult<std::unique_ptr<host::Link>> open_any_link(const host::BoardAddress& address);

// The exit code for an error (exit_codes.hpp).
int exit_code_for(const host::HostError& error);
// Prints "tetrapulse COMMAND: <error>" on stderr; returns exit_code_for(error).
int report_failure(const char* command, const host::HostError& error);

}  // namespace tetrapulse::cli
