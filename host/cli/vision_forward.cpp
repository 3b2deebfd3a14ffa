#include "vision_forward.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "exit_codes.hpp"
#include "vision_commands.hpp"

namespace tetrapulse::cli {

int run_vision_program(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) self = fs::absolute(argv[0], ec);
  const fs::path program = self.parent_path() / "tetrapulse-vision";
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  ::execv(program.c_str(), args.data());
  const int error = errno;
  std::fprintf(stderr, "tetrapulse %s: cannot run %s (%s); sim, localize, eval and demo are that program's\n",
               argc > 1 ? argv[1] : "", program.c_str(), std::strerror(error));
  return kExitFailure;
}

void add_vision_forwarders(CLI::App& app, int argc, char** argv, int* result) {
  for (const VisionCommand& c : kVisionCommands) {
    auto* cmd = app.add_subcommand(c.name, c.summary);
    // Everything after the name, --help included, is the vision program's to read.
    cmd->prefix_command();
    cmd->set_help_flag();
    cmd->allow_extras();
    cmd->footer("Run by tetrapulse-vision: `tetrapulse " + std::string(c.name) + " --help` for its options.");
    cmd->callback([argc, argv, result] { *result = run_vision_program(argc, argv); });
  }
}

}  // namespace tetrapulse::cli
