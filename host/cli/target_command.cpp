// `tetrapulse target optimize` and `tetrapulse target check`: the paper's target
// geometry optimisation (hardware/optimizer) glued to rig-dataset targets.yaml files.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "target_report.hpp"
#include "tetrapulse/hardware/target_analysis.hpp"
#include "tetrapulse/hardware/target_optimizer.hpp"
#include "tetrapulse/hardware/top_view.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse::cli {

namespace {

using hardware::Eq1Limits;

// Eq. 1's limits, shared by both subcommands. w and the top-view limits default to
// values that depend on the others (eq1_score.hpp, top_view.hpp).
struct LimitOptions {
  Eq1Limits limits;
  double top_d1 = 0, top_d2 = 0, top_h = 0;
  CLI::Option* w = nullptr;
  CLI::Option* top_d1_option = nullptr;
  CLI::Option* top_d2_option = nullptr;
  CLI::Option* top_h_option = nullptr;

  void add_to(CLI::App* cmd) {
    cmd->add_option("--d1", limits.d1, "D1: shortest marker distance (m)")->capture_default_str();
    cmd->add_option("--d2", limits.d2, "D2: longest marker distance (m)")->capture_default_str();
    cmd->add_option("--h", limits.h, "H: smallest face height, marker to opposite face (m)")->capture_default_str();
    w = cmd->add_option("--w", limits.w, "weight of s_min against s_avg (default (6n-2)/(6n): 2/3 for one target)");
    top_d1_option = cmd->add_option("--top-d1", top_d1, "D1 of the top view (default D1/2)");
    top_d2_option = cmd->add_option("--top-d2", top_d2, "D2 of the top view (default D2)");
    top_h_option =
        cmd->add_option("--top-h", top_h, "H of the top view: smallest projected triangle altitude (default H/2)");
  }

  Eq1Limits resolved(int targets) const {
    Eq1Limits l = limits;
    if (w->count() == 0) l.w = hardware::default_weight(6 * targets);
    return l;
  }

  Eq1Limits top_view(const Eq1Limits& l) const {
    Eq1Limits top = hardware::default_top_view_limits(l);
    if (top_d1_option->count() > 0) top.d1 = top_d1;
    if (top_d2_option->count() > 0) top.d2 = top_d2;
    if (top_h_option->count() > 0) top.h = top_h;
    return top;
  }
};

struct OptimizeOptions {
  int targets = 1;
  int restarts = 1000;
  uint64_t seed = 1;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  double marker_diameter = 0.03;
  std::string out;
  LimitOptions limits;
};

struct CheckOptions {
  std::string file;
  hardware::ViewSphere sphere;
  bool json = false;
  LimitOptions limits;
};

void fail(const char* command, const std::string& message) {
  std::fprintf(stderr, "tetrapulse target %s: %s\n", command, message.c_str());
}

// Every setting that shapes the result, so the line reproduces the file exactly.
std::string reproducing_command(const OptimizeOptions& o, const hardware::OptimizerSettings& s) {
  return fmt::format("tetrapulse target optimize --targets {} --d1 {} --d2 {} --h {} --w {} --top-d1 {} --top-d2 {} "
                     "--top-h {} --restarts {} --seed {} --marker-diameter {} --out {}",
                     s.targets, s.limits.d1, s.limits.d2, s.limits.h, s.limits.w, s.top_view.d1, s.top_view.d2,
                     s.top_view.h, s.restarts, s.seed, o.marker_diameter, o.out);
}

TargetsFile targets_file(const hardware::OptimizedTargets& result, const OptimizeOptions& o) {
  TargetsFile file;
  file.modulation.kind = ModulationKind::kConstant;  // codes come from `tetrapulse codebook`
  for (size_t i = 0; i < result.targets.size(); ++i) {
    Target t;
    t.id = static_cast<int>(i);
    t.name = fmt::format("optimised-{}-of-{}-seed-{}", i + 1, result.targets.size(), o.seed);
    t.marker_diameter_m = o.marker_diameter;
    for (int k = 0; k < 4; ++k) t.markers[k].position_m = result.targets[i][k];
    file.targets.push_back(t);
  }
  return file;
}

int run_optimize(const OptimizeOptions& o, bool w_given) {
  hardware::OptimizerSettings s;
  s.targets = o.targets;
  s.limits = o.limits.resolved(o.targets);
  s.top_view = o.limits.top_view(s.limits);
  s.restarts = o.restarts;
  s.seed = o.seed;
  s.threads = o.threads;
  s.lift = o.marker_diameter;
  if (auto problem = hardware::settings_problem(s)) {
    fail("optimize", *problem);
    return kExitUsage;
  }
  if (!(o.marker_diameter > 0 && o.marker_diameter < s.limits.d1)) {
    fail("optimize", fmt::format("marker-diameter must be positive and below d1 ({} m) so markers never touch, got {}",
                                 s.limits.d1, o.marker_diameter));
    return kExitUsage;
  }
  if (w_given && s.limits.w <= hardware::clustering_weight(6 * s.targets)) {
    std::fprintf(stderr,
                 "tetrapulse target optimize: warning: w = %g <= %g: for %d targets Eq. 1 then prefers distances "
                 "bunched at D1 and D2 over evenly spread ones\n",
                 s.limits.w, hardware::clustering_weight(6 * s.targets), s.targets);
  }
  const auto start = std::chrono::steady_clock::now();
  const std::optional<hardware::OptimizedTargets> result = hardware::optimize_targets(s);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result) {
    fail("optimize", "invalid settings");
    return kExitUsage;
  }
  if (result->score.violation > 0) {
    fail("optimize", fmt::format("no restart met the constraints (best misses them by {:.6f} m); lower --h or "
                                 "widen [--d1, --d2]",
                                 result->score.violation));
    return kExitFailure;
  }
  std::string text = fmt::format("# {}\n", reproducing_command(o, s));
  text += fmt::format("# Eq. 1 (Breitenmoser et al. 2011): s_min {:.6f} m, s_avg {:.6f} m, f {:.6f} m; "
                      "top view: s_min {:.6f} m. Restart {} of {}.\n",
                      result->score.spread.s_min, result->score.spread.s_avg, result->score.f,
                      result->top_score.spread.s_min, result->restart, s.restarts);
  text += "# Target frame: z up, support plane z = 0; positions in metres. Unmodulated: assign codes with "
          "`tetrapulse codebook`.\n";
  text += format_targets_yaml(targets_file(*result, o));
  if (auto written = write_text_file(o.out, text); !written) {
    fail("optimize", written.error().what());
    return kExitFailure;
  }
  std::printf("%s: %d target%s, s_min %.6f m, s_avg %.6f m, f %.6f m; top view s_min %.6f m "
              "(restart %d of %d, %d candidates, %.2f s on %d threads)\n",
              o.out.c_str(), s.targets, s.targets == 1 ? "" : "s", result->score.spread.s_min,
              result->score.spread.s_avg, result->score.f, result->top_score.spread.s_min, result->restart,
              s.restarts, result->candidates, seconds, s.threads);
  return kExitOk;
}

int run_check(const CheckOptions& o) {
  const DatasetResult<TargetsFile> file = read_targets_yaml(o.file);
  if (!file) {
    fail("check", file.error().what());
    return kExitBadInput;
  }
  const int n = static_cast<int>(file->targets.size());
  hardware::AnalysisSettings s;
  s.limits = o.limits.resolved(n);
  s.top_view = o.limits.top_view(s.limits);
  s.sphere = o.sphere;
  std::vector<hardware::Markers> markers;
  std::vector<double> diameters;
  for (const Target& t : file->targets) {
    hardware::Markers m;
    for (int k = 0; k < 4; ++k) m[k] = t.markers[k].position_m;
    markers.push_back(m);
    diameters.push_back(t.marker_diameter_m);
  }
  if (auto problem = hardware::analysis_problem(markers, s)) {
    fail("check", o.file + ": " + *problem);
    return kExitUsage;
  }
  const hardware::SystemAnalysis analysis = hardware::analyse_targets(markers, diameters, s);
  const std::string report = o.json ? format_target_check_json(o.file, *file, analysis, s)
                                    : format_target_check_text(o.file, *file, analysis, s);
  std::fputs(report.c_str(), stdout);
  return analysis.violations.empty() ? kExitOk : kExitCheckFailed;
}

}  // namespace

void add_target_command(CLI::App& app, int* result) {
  auto* target = app.add_subcommand("target", "Design and check target geometries (the paper's Eq. 1)");
  target->require_subcommand(1);

  auto optimize_options = std::make_shared<OptimizeOptions>();
  auto* optimize = target->add_subcommand(
      "optimize", "Optimise the marker layout of N targets jointly (Eq. 1, Nelder-Mead from random starts)");
  optimize->add_option("--targets", optimize_options->targets, "number of targets n")->capture_default_str();
  optimize_options->limits.add_to(optimize);
  optimize->add_option("--restarts", optimize_options->restarts, "random starts")->capture_default_str();
  optimize->add_option("--seed", optimize_options->seed, "seed: the same seed gives the same targets")
      ->capture_default_str();
  optimize->add_option("--threads", optimize_options->threads, "worker threads (the result does not depend on it)")
      ->capture_default_str();
  optimize->add_option("--marker-diameter", optimize_options->marker_diameter, "marker diameter (m)")
      ->capture_default_str();
  optimize->add_option("--out", optimize_options->out, "targets.yaml to write")->required();
  optimize->callback([optimize_options, result] {
    *result = run_optimize(*optimize_options, optimize_options->limits.w->count() > 0);
  });

  auto check_options = std::make_shared<CheckOptions>();
  auto* check = target->add_subcommand(
      "check", "Report Eq. 1, face heights, degeneracy and pose conditioning of a targets.yaml (exit 6 when a "
               "constraint fails)");
  check->add_option("file", check_options->file, "targets.yaml to check")->required();
  check_options->limits.add_to(check);
  check->add_option("--view-distance", check_options->sphere.distance, "camera distance for the pose conditioning (m)")
      ->capture_default_str();
  check->add_option("--views", check_options->sphere.views, "viewing directions over the sphere")
      ->capture_default_str();
  check->add_flag("--json", check_options->json, "print JSON instead of text");
  check->callback([check_options, result] { *result = run_check(*check_options); });
}

}  // namespace tetrapulse::cli
