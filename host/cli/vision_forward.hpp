#pragma once
// tetrapulse hands the vision commands (vision_commands.hpp) to tetrapulse-vision.
#include <CLI/CLI.hpp>

namespace tetrapulse::cli {

// Replaces this process with tetrapulse-vision (found beside this program) and
// the same arguments. Returns only when that fails, with the exit code, having
// said why on stderr.
int run_vision_program(int argc, char** argv);

// Entries in `app` for the help text; running one hands over like run_vision_program.
void add_vision_forwarders(CLI::App& app, int argc, char** argv, int* result);

}  // namespace tetrapulse::cli
