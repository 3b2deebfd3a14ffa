// `tetrapulse status [--watch]`: a board's sync state, counters and update state.
#include <chrono>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "stop_signal.hpp"

namespace tetrapulse::cli {
namespace {

struct StatusArgs {
  BoardOptions board;
  bool watch = false;
  int interval_ms = 1000;
  int count = 0;
};

int run_status(const StatusArgs& a) {
  const std::atomic<bool>& stop = stop_on_signals();
  auto board = open_board(a.board);
  if (!board) return report_failure("status", board.error());
  const int polls = a.watch ? a.count : 1;
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; polls == 0 || i < polls; ++i) {
    if (i > 0) {
      next += std::chrono::milliseconds(a.interval_ms);
      while (!stop && std::chrono::steady_clock::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (stop) break;
    }
    auto status = (*board)->status();
    if (!status) return report_failure("status", status.error());
    if (a.board.json) {
      fmt::print("{}\n", status_json((*board)->name(), *status));
    } else {
      fmt::print("{}: {}\n", (*board)->name(), format_status(*status));
    }
    std::fflush(stdout);
  }
  return kExitOk;
}

}  // namespace

void add_status_command(CLI::App& app, int* result) {
  auto a = std::make_shared<StatusArgs>();
  auto* cmd = app.add_subcommand("status", "Show a board's sync state, error counters and update state");
  add_board_options(cmd, &a->board);
  cmd->add_flag("--watch", a->watch, "Keep asking, one line (or JSON object) per answer, until Ctrl-C");
  cmd->add_option("--interval-ms", a->interval_ms, "Time between answers with --watch")
      ->check(CLI::Range(10, 3600000))
      ->capture_default_str();
  cmd->add_option("--count", a->count, "With --watch: stop after this many answers (0: until stopped)")
      ->check(CLI::Range(0, 1000000000));
  cmd->callback([a, result] { *result = run_status(*a); });
}

}  // namespace tetrapulse::cli
