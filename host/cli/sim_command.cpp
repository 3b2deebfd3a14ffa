// tetrapulse sim: the virtual rig. Writes a rig dataset from a scenario.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "vision_commands.hpp"
#include "tetrapulse/host/sim_rig.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"
#include "tetrapulse/sim/dataset_simulation.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::cli {

namespace {

namespace fs = std::filesystem;

struct SimArgs {
  std::string scenario;
  std::string out;
  std::optional<uint64_t> seed;
  std::optional<int64_t> frames;
  bool ci = false;
  bool force = false;
  bool list = false;
  bool host_boards = false;
  std::string print;
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "tetrapulse sim: %s\n", message.c_str());
  return code;
}

int list_builtins() {
  for (const sim::BuiltinScenario& b : sim::builtin_scenarios()) {
    auto s = sim::parse_scenario(b.text, b.name);
    fmt::print("{:<12} {}\n", b.name, s ? s->description : std::string("(unreadable: ") + s.error().what() + ")");
  }
  return kExitOk;
}

// An existing folder is written into only with --force, and then only our own files are replaced.
int prepare_output(const SimArgs& a) {
  std::error_code ec;
  if (!fs::exists(a.out, ec)) return kExitOk;
  if (!fs::is_directory(a.out, ec)) return fail(kExitUsage, a.out + ": exists and is not a folder");
  if (fs::is_empty(a.out, ec)) return kExitOk;
  if (!a.force) return fail(kExitUsage, a.out + ": exists and is not empty (--force writes into it)");
  const fs::path frames = fs::path(a.out) / "frames";
  if (fs::is_directory(frames, ec)) {
    for (const auto& entry : fs::directory_iterator(frames, ec)) {
      if (entry.path().extension() == ".png") fs::remove(entry.path(), ec);
    }
  }
  fs::remove(fs::path(a.out) / "groundtruth.csv", ec);
  return kExitOk;
}

int run_sim(const SimArgs& a) {
  if (a.list) return list_builtins();
  if (!a.print.empty()) {
    const sim::BuiltinScenario* b = sim::find_builtin_scenario(a.print);
    if (b == nullptr) return fail(kExitUsage, a.print + ": not a built-in scenario (tetrapulse sim --list)");
    fmt::print("{}", b->text);
    return kExitOk;
  }
  if (a.scenario.empty()) return fail(kExitUsage, "give a SCENARIO (a built-in name or a YAML file), or --list");
  if (a.out.empty()) return fail(kExitUsage, "--out DIR is required");
  auto scenario = sim::load_scenario(a.scenario);
  if (!scenario) return fail(kExitBadInput, scenario.error().what());
  if (const int r = prepare_output(a); r != kExitOk) return r;
  sim::SimulationOptions options;
  options.out = a.out;
  options.seed = a.seed;
  options.frames = a.frames;
  options.ci = a.ci;
  sim::SimulationSummary summary;
  if (a.host_boards) {
    auto done = host::simulate_with_host_boards(*scenario, options);
    if (!done) return fail(kExitFailure, done.error().what());
    summary = *done;
  } else {
    auto done = sim::simulate_dataset(*scenario, options);
    if (!done) return fail(kExitFailure, done.error().what());
    summary = *done;
  }
  fmt::print("tetrapulse sim: {} (seed {}): {} frames written, {} dropped, {} ground-truth poses in {}\n",
             scenario->name, summary.seed, summary.frames_written, summary.frames_dropped,
             summary.groundtruth_rows, a.out);
  return kExitOk;
}

}  // namespace

void add_sim_command(CLI::App& app, int* result) {
  auto args = std::make_shared<SimArgs>();
  auto* cmd = app.add_subcommand("sim", vision_summary("sim"));
  cmd->add_option("scenario", args->scenario, "A built-in scenario's name (--list) or a scenario YAML file");
  cmd->add_option("--out", args->out, "Dataset folder to write");
  cmd->add_option("--seed", args->seed, "Random seed (default: the scenario's)");
  cmd->add_option("--frames", args->frames, "Number of frame numbers (default: the scenario's count)")
      ->check(CLI::Range(int64_t{1}, int64_t{10'000'000}));
  cmd->add_flag("--ci", args->ci, "The scenario's CI-sized variant (its ci_count frames)");
  cmd->add_flag("--force", args->force, "Write into a folder that is not empty");
  cmd->add_flag("--host-boards", args->host_boards,
                "Configure and synchronise the simulated boards through the host's Board, GpioSync and CanSync "
                "code over simulated links, as on a real rig (the dataset is the same)");
  cmd->add_flag("--list", args->list, "List the built-in scenarios");
  cmd->add_option("--print", args->print, "Print a built-in scenario's YAML (a starting point for your own)");
  cmd->footer("Scenario format: sim/SCENARIOS.md. Dataset format: docs/rig-dataset.md.");
  cmd->callback([args, result] { *result = run_sim(*args); });
}

}  // namespace tetrapulse::cli
