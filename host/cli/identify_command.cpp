// `tetrapulse identify`: make a board visible to a person (SPEC.md §2.3 Identify).
#include <map>
#include <memory>

#include <fmt/format.h>

#include "board_options.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"

namespace tetrapulse::cli {
namespace {

struct IdentifyArgs {
  BoardOptions board;
  std::string pattern = "blink";
  int duration_ms = 5000;
};

const std::map<std::string, protocol::IdentifyPattern> kPatterns = {{"stop", protocol::IdentifyPattern::kStop},
                                                                   {"blink", protocol::IdentifyPattern::kBlinkAll},
                                                                   {"chase", protocol::IdentifyPattern::kChase},
                                                                   {"count", protocol::IdentifyPattern::kCountIndex}};

int run_identify(const IdentifyArgs& a) {
  auto board = open_board(a.board);
  if (!board) return report_failure("identify", board.error());
  auto done = (*board)->identify(kPatterns.at(a.pattern), static_cast<uint16_t>(a.duration_ms));
  if (!done) return report_failure("identify", done.error());
  if (a.board.json) {
    fmt::print("{}\n", JsonObject().str("address", (*board)->name()).str("pattern", a.pattern).num("duration_ms", a.duration_ms).text());
  } else {
    fmt::print("{}: identify {} for {}\n", (*board)->name(), a.pattern,
               a.duration_ms == 0 ? std::string("until stopped") : fmt::format("{} ms", a.duration_ms));
  }
  return kExitOk;
}

}  // namespace

void add_identify_command(CLI::App& app, int* result) {
  auto a = std::make_shared<IdentifyArgs>();
  auto* cmd = app.add_subcommand("identify", "Make a board's markers blink so a person can find it");
  add_board_options(cmd, &a->board);
  cmd->add_option("--pattern", a->pattern,
                  "blink: all markers together; chase: one after another; count: marker i blinks i+1 times; "
                  "stop: back to the codes")
      ->check(CLI::IsMember({"stop", "blink", "chase", "count"}))
      ->capture_default_str();
  cmd->add_option("--duration-ms", a->duration_ms, "How long; 0 until `--pattern stop`")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->callback([a, result] { *result = run_identify(*a); });
}

}  // namespace tetrapulse::cli
