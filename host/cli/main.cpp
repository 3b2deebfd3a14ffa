// tetrapulse: coded LED targets, identified 6D poses from one camera.
#include "commands.hpp"
#include "exit_codes.hpp"
#include "run_app.hpp"
#include "vision_commands.hpp"
#include "vision_forward.hpp"

int main(int argc, char** argv) {
  using namespace tetrapulse::cli;
  if (argc > 1 && vision_summary(argv[1]) != nullptr) return run_vision_program(argc, argv);
  CLI::App app{"tetrapulse: identified 6D poses of coded LED targets from one camera"};
  app.footer(kExitCodesHelp);
  app.require_subcommand(1);
  int result = kExitOk;
  add_version_command(app, &result);
  add_codebook_command(app, &result);
  add_target_command(app, &result);
  add_vision_forwarders(app, argc, argv, &result);
  add_list_command(app, &result);
  add_info_command(app, &result);
  add_config_command(app, &result);
  add_identify_command(app, &result);
  add_status_command(app, &result);
  add_flash_command(app, &result);
  add_sync_command(app, &result);
  return run_app(app, argc, argv, result);
}
