// tetrapulse-vision: the commands of tetrapulse that read or write images
// (vision_commands.hpp); `tetrapulse sim|localize|eval|demo` runs this program.
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "exit_codes.hpp"

int main(int argc, char** argv) {
  using namespace tetrapulse::cli;
  CLI::App app{"tetrapulse: identified 6D poses of coded LED targets from one camera (vision commands)"};
  app.name("tetrapulse");
  app.footer(kExitCodesHelp);
  app.require_subcommand(1);
  int result = kExitOk;
  add_sim_command(app, &result);
  add_localize_command(app, &result);
  add_eval_command(app, &result);
  add_demo_command(app, &result);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tetrapulse: internal error: %s\n", e.what());
    return kExitFailure;
  }
  return result;
}
