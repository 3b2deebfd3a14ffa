#pragma once
// The common end of both programs' main(): parse, run the chosen command, map errors
// to exit codes (exit_codes.hpp).
#include <CLI/CLI.hpp>

namespace tetrapulse::cli {

// Parses argv into `app` (whose callbacks store their exit code in `result`) and returns
// the exit code: usage errors kExitUsage, an escaped exception kExitFailure.
int run_app(CLI::App& app, int argc, char** argv, const int& result);

}  // namespace tetrapulse::cli
