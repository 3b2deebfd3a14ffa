#pragma once
// What `tetrapulse codebook` and `tetrapulse codebook check` share: the
// constraint options, the spec they make (SPEC.md §8.4 defaults, then the
// options) and how both speak about it.
#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <tl/expected.hpp>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/codebook/codebook.hpp"

namespace tetrapulse::cli {

inline constexpr const char* kCodebookDefaultsHelp =
    "Defaults by mode (any constraint option overrides them):\n"
    "  synchronized (default): --length 12, --distance 3 at equal phase, --weights 40%-60% of the\n"
    "      length rounded (5-7 for 12 bits), --max-zero-run 2 with on_off, none with two_level\n"
    "  --free-running: --length 15, --distance 3 under every cyclic shift (and from the code's own\n"
    "      shifts), --weights any, --max-zero-run 3 with on_off, none with two_level\n"
    "  both: --max-one-run none, --per marker, --seed 1, --bit-period-ns 10000000, ids 1..N,\n"
    "      geometry hardware/targets/paper-half-active.yaml (built in)\n"
    "Runs are cyclic: codes repeat. `check` takes the mode from the file's timebase and modulation.";

// Constraint options shared by generation and check; empty ones take the mode's default.
// Constraint options; empty ones take the mode's recommended value.
struct CodebookConstraintArgs {
  std::optional<int> length;
  std::optional<int> distance;
  std::string weights;       // "A-B" or "any"
  std::string max_zero_run;  // "K" or "none"
  std::string max_one_run;   // "K" or "none"
  uint32_t iterations = protocol::CodebookSpec{}.search_iterations;
};

// A command-line problem: one line, exit kExitUsage.
struct CommandLineError {
  std::string message;
};

void add_codebook_constraint_options(CLI::App* cmd, CodebookConstraintArgs* a);

// The recommended spec for the timing and modulation (and a file's code
// length, when checking one), with the options given applied.
tl::expected<protocol::CodebookSpec, CommandLineError> codebook_spec(const CodebookConstraintArgs& a,
                                                                     protocol::CodeTiming timing,
                                                                     ModulationKind modulation,
                                                                     std::optional<int> file_length);

protocol::ZeroBit zero_bit(ModulationKind modulation);

// "synchronized, 12 bits, distance >= 3, weights 5-7, zero runs <= 2"
std::string describe_codebook_spec(const protocol::CodebookSpec& s);

// Prints "tetrapulse codebook: MESSAGE" on stderr.
void codebook_error(const std::string& message);

// Registers `check` under the `codebook` command.
void add_codebook_check_command(CLI::App* codebook, int* result);

}  // namespace tetrapulse::cli
