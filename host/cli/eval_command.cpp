// tetrapulse eval: a poses file against its dataset's ground truth.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "evaluation_report.hpp"
#include "exit_codes.hpp"
#include "vision_commands.hpp"
#include "tetrapulse/datasets/pose_evaluation.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::cli {

namespace {

struct EvalArgs {
  std::string dataset;
  std::string poses;
  bool json = false;
  std::optional<double> max_position_error;     // m, mean over all
  std::optional<double> max_orientation_error;  // deg, mean over all
  std::optional<double> min_coverage;           // fraction
  std::optional<size_t> max_misidentified;
  std::optional<int64_t> max_latency;           // frames
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "tetrapulse eval: %s\n", message.c_str());
  return code;
}

// Each threshold given that does not hold, one line each.
std::string check_thresholds(const EvalArgs& a, const Evaluation& e) {
  std::string failed;
  const TargetEvaluation& all = e.overall;
  if (a.max_position_error && !(all.position_m.mean <= *a.max_position_error)) {
    failed += fmt::format("mean position error {:.4f} m > {} m\n", all.position_m.mean, *a.max_position_error);
  }
  const double orientation_deg = all.orientation_rad.mean * 180 / M_PI;
  if (a.max_orientation_error && !(orientation_deg <= *a.max_orientation_error)) {
    failed += fmt::format("mean orientation error {:.4f} deg > {} deg\n", orientation_deg, *a.max_orientation_error);
  }
  if (a.min_coverage && !(all.coverage() >= *a.min_coverage)) {
    failed += fmt::format("coverage {:.4f} < {}\n", all.coverage(), *a.min_coverage);
  }
  if (a.max_misidentified && all.misidentified > *a.max_misidentified) {
    failed += fmt::format("{} misidentified rows > {}\n", all.misidentified, *a.max_misidentified);
  }
  if (a.max_latency) {
    for (const TargetEvaluation& t : e.targets)
      if (t.episodes > 0 && t.max_latency_frames > *a.max_latency) {
        failed += fmt::format("target {}: identification latency {} frames > {}\n", t.target, t.max_latency_frames,
                              *a.max_latency);
      }
  }
  return failed;
}

// A dataset tetrapulse sim wrote keeps its scenario (scenario.yaml): the clocks of
// boards that ran free are known, and coverage counts the frames their markers were
// truly lit (over a long recording a 200 ppm crystal drifts whole bits off the
// nominal clock). Without it, or when it does not load, the nominal clock (said so).
EvaluationOptions evaluation_options_for(const RigDataset& dataset) {
  EvaluationOptions options;
  const std::string path = dataset.path_of("scenario.yaml");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return options;
  auto scenario = sim::load_scenario(path);
  if (!scenario) {
    std::fprintf(stderr, "tetrapulse eval: %s: %s; free-running boards counted by their nominal clocks\n",
                 path.c_str(), scenario.error().what().c_str());
    return options;
  }
  options.board_clocks = sim::free_running_code_clocks(*scenario);
  return options;
}

int run_eval(const EvalArgs& a) {
  auto dataset = RigDataset::open(a.dataset);
  if (!dataset) return fail(kExitBadInput, dataset.error().what());
  auto poses = read_poses_csv(a.poses);
  if (!poses) return fail(kExitBadInput, poses.error().what());
  auto evaluation = evaluate_poses(*dataset, *poses, a.poses, evaluation_options_for(*dataset));
  if (!evaluation) return fail(kExitBadInput, evaluation.error().what());
  if (a.json) {
    std::fputs(evaluation_json(*evaluation).c_str(), stdout);
  } else {
    std::fputs(evaluation_table(*evaluation, "").c_str(), stdout);
  }
  const std::string failed = check_thresholds(a, *evaluation);
  if (!failed.empty()) {
    std::fprintf(stderr, "tetrapulse eval: check failed: %s", failed.c_str());
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace

void add_eval_command(CLI::App& app, int* result) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", vision_summary("eval"));
  cmd->add_option("dataset", args->dataset, "Rig dataset folder with groundtruth.csv")->required();
  cmd->add_option("poses", args->poses, "poses.csv written by tetrapulse localize")->required();
  cmd->add_flag("--json", args->json, "Print JSON instead of the table");
  cmd->add_option("--max-position-error", args->max_position_error, "Fail (exit 6) when the mean position error exceeds this (m)");
  cmd->add_option("--max-orientation-error", args->max_orientation_error,
                  "Fail when the mean orientation error exceeds this (degrees)");
  cmd->add_option("--min-coverage", args->min_coverage, "Fail when coverage is below this fraction (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--max-misidentified", args->max_misidentified, "Fail when more rows than this are misidentified");
  cmd->add_option("--max-latency", args->max_latency, "Fail when identification takes more frames than this");
  cmd->footer(
      "Errors: position |t - t_true|, orientation angle of R_true^T R. Coverage: frames with a pose / frames where\n"
      "the target had >= 3 markers lit and in view. Latency: frames from a target becoming visible to its first\n"
      "pose. Misidentified: rows whose pose is not that of the target they name. Boards that run free are\n"
      "counted by their own clocks when the dataset holds the scenario.yaml tetrapulse sim writes.");
  cmd->callback([args, result] { *result = run_eval(*args); });
}

}  // namespace tetrapulse::cli
