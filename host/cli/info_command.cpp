// `tetrapulse info`: what a board is (model, firmware, serial, capabilities).
#include <memory>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"

namespace tetrapulse::cli {
namespace {

int run_info(const BoardOptions& o) {
  auto board = open_board(o);
  if (!board) return report_failure("info", board.error());
  auto info = (*board)->info();
  if (!info) return report_failure("info", info.error());
  fmt::print("{}", o.json ? info_json((*board)->name(), *info) + "\n" : format_info((*board)->name(), *info));
  return kExitOk;
}

}  // namespace

void add_info_command(CLI::App& app, int* result) {
  auto o = std::make_shared<BoardOptions>();
  auto* cmd = app.add_subcommand("info", "Show what a board is: model, firmware, serial number, capabilities");
  add_board_options(cmd, o.get());
  cmd->callback([o, result] { *result = run_info(*o); });
}

}  // namespace tetrapulse::cli
