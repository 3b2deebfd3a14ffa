#pragma once
// Every subcommand registers itself on the app; when it runs it stores its exit
// code (exit_codes.hpp) in *result.
#include <CLI/CLI.hpp>

namespace tetrapulse::cli {

void add_version_command(CLI::App& app, int* result);
void add_codebook_command(CLI::App& app, int* result);
void add_sim_command(CLI::App& app, int* result);
void add_target_command(CLI::App& app, int* result);
void add_localize_command(CLI::App& app, int* result);
void add_eval_command(CLI::App& app, int* result);
void add_demo_command(CLI::App& app, int* result);
void add_list_command(CLI::App& app, int* result);
void add_info_command(CLI::App& app, int* result);
void add_config_command(CLI::App& app, int* result);
void add_identify_command(CLI::App& app, int* result);
void add_status_command(CLI::App& app, int* result);
void add_flash_command(CLI::App& app, int* result);
void add_sync_command(CLI::App& app, int* result);
void add_record_command(CLI::App& app, int* result);

}  // namespace tetrapulse::cli
