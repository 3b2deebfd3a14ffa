// tetrapulse-vision: the commands of tetrapulse that read or write images
// (vision_commands.hpp); `tetrapulse sim|localize|eval|demo` runs this program.
#include "commands.hpp"
#include "exit_codes.hpp"
#include "run_app.hpp"

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
  add_record_command(app, &result);
  return run_app(app, argc, argv, result);
}
