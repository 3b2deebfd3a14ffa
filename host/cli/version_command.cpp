#include <fmt/format.h>

#include "commands.hpp"
#include "exit_codes.hpp"

namespace tetrapulse::cli {

void add_version_command(CLI::App& app, int* result) {
  auto* cmd = app.add_subcommand("version", "Print the tetrapulse version");
  cmd->callback([result] {
    fmt::print("tetrapulse {}\n", TETRAPULSE_VERSION);
    *result = kExitOk;
  });
}

}  // namespace tetrapulse::cli
