// tetrapulse demo: the virtual rig end to end. Simulates paper-exp1 and swarm (or
// the scenarios given with --scenario: built-in names or YAML files), localizes
// them, evaluates against ground truth, prints the accuracy table and writes a trajectory plot, an annotated frame strip and an overlay video (every
// frame, measured and true poses drawn) per scenario.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "commands.hpp"
#include "demo_simulation.hpp"
#include "evaluation_report.hpp"
#include "exit_codes.hpp"
#include "vision_commands.hpp"
#include "overlay_video.hpp"
#include "pose_overlay.hpp"
#include "progress_bar.hpp"
#include "stop_signal.hpp"
#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/datasets/pose_evaluation.hpp"
#include "tetrapulse/datasets/pose_writer.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"
#include "trajectory_plot.hpp"

namespace tetrapulse::cli {

namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string out = "out/demo";
  std::vector<std::string> scenarios;  // empty: kDemoScenarios
  double seconds = 8;
  bool quiet = false;
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "tetrapulse demo: %s\n", message.c_str());
  return code;
}

constexpr const char* kDemoScenarios[] = {"paper-exp1", "swarm"};
constexpr int kStripFrames = 6;

// The localizer's rows, and the poses of each frame for the overlays.
struct Localized {
  std::vector<PoseRecord> rows;
  size_t skipped = 0;    // frames that could not be localized (each named on stderr)
  bool stopped = false;  // by SIGINT or SIGTERM: poses.csv holds the frames so far
};

// Also writes `overlay_path`: every frame with the measured poses and the true ones.
DatasetResult<Localized> localize_dataset(const RigDataset& dataset, const std::string& poses_csv,
                                          const std::string& overlay_path, bool quiet) {
  Localizer localizer(dataset.camera(), dataset.targets());
  auto writer = PoseWriter::open(poses_csv, PoseFormat::kCsv, dataset.targets());
  if (!writer) return tl::unexpected(writer.error());
  auto overlay = OverlayVideo::create(overlay_path, dataset.camera(), dataset.targets());
  if (!overlay) return tl::unexpected(overlay.error());
  std::map<int64_t, std::vector<OverlayPose>> truth_of;
  for (const GroundTruthRecord& g : dataset.groundtruth())
    if (const Target* t = dataset.targets().find(g.target)) truth_of[g.frame].push_back({t, g.pose.pose()});
  auto source = dataset_frames(dataset);
  ProgressBar progress(source->count(), !quiet);
  Localized out;
  LocalizeHooks hooks;
  hooks.stop = &stop_on_signals();
  hooks.on_skip = [&](const Frame&, const DatasetError& why) {
    progress.finish();  // clears the bar's line for the message
    fmt::print(stderr, "tetrapulse demo: skipped {}\n", why.what());
    progress.advance();
  };
  auto frames = localize_frames(
      *source, localizer,
      [&](const Frame& f, const std::vector<TargetPose>& poses) {
        for (const TargetPose& p : poses) {
          if (auto r = writer->write(f.frame, p); !r) return r;
          out.rows.push_back(
              PoseRecord{f.frame, p.mid_exposure_ns, p.target_id, PoseFields::from(p.pose), p.markers, p.rms_px});
        }
        const auto truth = truth_of.find(f.frame);
        if (auto r = overlay->add(f, poses, truth == truth_of.end() ? std::vector<OverlayPose>{} : truth->second); !r) return r;
        progress.advance();
        return writer->flush();  // whole frames reach the file as they come
      },
      hooks);
  progress.finish();
  if (auto r = overlay->close(); !r) return tl::unexpected(r.error());
  if (!frames) return tl::unexpected(frames.error());
  if (auto r = writer->close(); !r) return tl::unexpected(r.error());
  out.skipped = frames->skipped + dataset.skipped_lines().size();
  out.stopped = frames->stopped;
  return out;
}

// Positions for the plot: the camera in each target's frame when the camera
// moves (the paper's Fig. 5: the quadrotor over its landmark), else each target
// in the camera frame.
Eigen::Vector3d plotted(const Pose& pose, bool camera_moves) { return camera_moves ? pose.inverse().t : pose.t; }

cv::Mat trajectory_figure(const RigDataset& dataset, const Localized& localized, const std::string& name,
                          bool camera_moves) {
  std::map<int64_t, double> seconds;
  for (const FrameRecord& f : dataset.frames()) seconds[f.frame] = double(f.timestamp_ns - dataset.frames()[0].timestamp_ns) * 1e-9;
  std::map<std::pair<int64_t, int>, Pose> truth;
  std::map<int, Trajectory> by_target;
  for (const GroundTruthRecord& g : dataset.groundtruth()) {
    truth[{g.frame, g.target}] = g.pose.pose();
    by_target[g.target].truth.push_back({seconds[g.frame], plotted(g.pose.pose(), camera_moves)});
  }
  for (const PoseRecord& p : localized.rows) {
    Trajectory& tr = by_target[p.target];
    tr.measured.push_back({seconds[p.frame], plotted(p.pose.pose(), camera_moves)});
    const auto it = truth.find({p.frame, p.target});
    if (it != truth.end()) {
      tr.error.push_back({seconds[p.frame], Eigen::Vector3d((p.pose.pose().t - it->second.t).norm(), 0, 0)});
    }
  }
  std::vector<Trajectory> trajectories;
  for (auto& [id, tr] : by_target) {
    tr.label = by_target.size() > 1 ? fmt::format("id {}", id) : "";
    trajectories.push_back(std::move(tr));
  }
  return plot_trajectories(trajectories, name + ": ground truth (red) and measured (blue), positions in cm",
                           camera_moves ? "camera position in the target frame" : "target positions in the camera frame");
}

DatasetResult<cv::Mat> overlay_strip(const RigDataset& dataset, const Localized& localized) {
  const CameraModel camera(dataset.camera());
  std::map<int64_t, std::vector<const PoseRecord*>> rows_of;
  for (const PoseRecord& p : localized.rows) rows_of[p.frame].push_back(&p);
  std::map<int64_t, std::vector<const GroundTruthRecord*>> truth_of;
  for (const GroundTruthRecord& g : dataset.groundtruth()) truth_of[g.frame].push_back(&g);
  std::vector<size_t> with_poses;
  for (size_t i = 0; i < dataset.frames().size(); ++i)
    if (rows_of.count(dataset.frames()[i].frame)) with_poses.push_back(i);
  std::vector<cv::Mat> tiles;
  for (int k = 0; k < kStripFrames && !with_poses.empty(); ++k) {
    const size_t index = with_poses[size_t(k) * (with_poses.size() - 1) / (kStripFrames - 1)];
    auto image = dataset.load_image(index);
    if (!image) return tl::unexpected(image.error());
    const int64_t frame = dataset.frames()[index].frame;
    std::vector<OverlayPose> measured, truth;
    for (const PoseRecord* p : rows_of[frame])
      if (const Target* t = dataset.targets().find(p->target)) measured.push_back({t, p->pose.pose()});
    for (const GroundTruthRecord* g : truth_of[frame])
      if (const Target* t = dataset.targets().find(g->target)) truth.push_back({t, g->pose.pose()});
    tiles.push_back(overlay_frame(*image, camera, measured, truth, fmt::format("frame {}", frame)));
    if (with_poses.size() == 1) break;
  }
  return frame_strip(tiles, 3, tiles.empty() || tiles[0].cols <= 800 ? 0.75 : 0.45);
}

DatasetResult<void> write_png(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = !image.empty() && cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    return dataset_error(path, 0, std::string("cannot write: ") + e.what());
  }
  if (!ok) return dataset_error(path, 0, "cannot write the image");
  return {};
}

struct ScenarioOutcome {
  Evaluation evaluation;
  std::string folder;
  std::string name;  // the scenario's
  size_t frames = 0;
  size_t skipped = 0;
  bool stopped = false;  // by a signal, while localizing: nothing evaluated or drawn
};

// One scenario: simulate, localize, evaluate, draw. Errors name the file at fault.
// `name_or_path`: what --scenario gave, for a file whose scenario has no name.
DatasetResult<ScenarioOutcome> run_scenario(const sim::Scenario& scenario, const std::string& name_or_path,
                                            const DemoArgs& a, const DemoSimulation& simulate) {
  const std::string name = scenario.name.empty() ? fs::path(name_or_path).stem().string() : scenario.name;
  const std::string folder = (fs::path(a.out) / name).string();
  const std::string data = (fs::path(folder) / "dataset").string();
  std::error_code ec;
  fs::remove_all(data, ec);  // the demo's own dataset from an earlier run
  fs::create_directories(folder, ec);
  if (ec) return dataset_error(folder, 0, "cannot create the folder: " + ec.message());
  const int64_t frames = std::max<int64_t>(1, int64_t(a.seconds * 1e9 / double(scenario.frames.period_ns)));
  if (!a.quiet) fmt::print(stderr, "tetrapulse demo: {}: simulating {} frames\n", name, frames);
  if (auto s = simulate(scenario, data, frames); !s) return tl::unexpected(s.error());
  auto dataset = RigDataset::open(data);
  if (!dataset) return tl::unexpected(dataset.error());
  if (!a.quiet) fmt::print(stderr, "tetrapulse demo: {}: localizing\n", name);
  auto localized =
      localize_dataset(*dataset, (fs::path(folder) / "poses.csv").string(), (fs::path(folder) / "overlay.avi").string(), a.quiet);
  if (!localized) return tl::unexpected(localized.error());
  if (localized->stopped) {
    ScenarioOutcome stopped;
    stopped.folder = folder;
    stopped.stopped = true;
    return stopped;
  }
  auto evaluation = evaluate_poses(*dataset, localized->rows, (fs::path(folder) / "poses.csv").string());
  if (!evaluation) return tl::unexpected(evaluation.error());
  const bool camera_moves = !std::holds_alternative<sim::StaticMotion>(scenario.camera_motion);
  if (auto r = write_png((fs::path(folder) / "trajectory.png").string(),
                         trajectory_figure(*dataset, *localized, name, camera_moves));
      !r) {
    return tl::unexpected(r.error());
  }
  auto strip = overlay_strip(*dataset, *localized);
  if (!strip) return tl::unexpected(strip.error());
  if (auto r = write_png((fs::path(folder) / "overlay.png").string(), *strip); !r) return tl::unexpected(r.error());
  return ScenarioOutcome{*evaluation, folder, name, dataset->frames().size(), localized->skipped, false};
}

int run_demo(const DemoArgs& a, const DemoSimulation& simulate) {
  const auto start = std::chrono::steady_clock::now();
  std::string markdown = evaluation_markdown_header();
  size_t skipped = 0;
  std::vector<std::string> names = a.scenarios;
  if (names.empty()) names.assign(std::begin(kDemoScenarios), std::end(kDemoScenarios));
  // Every scenario is read before the first is simulated: a typo costs no minutes.
  std::vector<sim::Scenario> scenarios;
  for (const std::string& n : names) {
    auto s = sim::load_scenario(n);
    if (!s) return fail(kExitUsage, s.error().what());
    scenarios.push_back(std::move(*s));
  }
  for (size_t i = 0; i < names.size(); ++i) {
    auto outcome = run_scenario(scenarios[i], names[i], a, simulate);
    if (!outcome) return fail(kExitFailure, outcome.error().what());
    if (outcome->stopped) {
      return fail(kExitFailure, fmt::format("stopped by a signal; {}/poses.csv has the frames localized so far",
                                            outcome->folder));
    }
    skipped += outcome->skipped;
    const Evaluation& e = outcome->evaluation;
    fmt::print("{}\n", evaluation_table(e, fmt::format("{} ({} frames)", outcome->name, outcome->frames)));
    fmt::print("  wrote {0}/poses.csv, {0}/trajectory.png, {0}/overlay.png, {0}/overlay.avi\n\n", outcome->folder);
    markdown += evaluation_markdown_row(e, outcome->name);
  }
  const std::string table = (fs::path(a.out) / "accuracy.md").string();
  if (auto r = write_text_file(table, markdown); !r) return fail(kExitFailure, r.error().what());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("tetrapulse demo: accuracy table in {}; done in {:.1f} s\n", table, seconds);
  if (skipped > 0) fmt::print(stderr, "tetrapulse demo: {} frames skipped (named above)\n", skipped);
  return skipped > 0 ? kExitSkipped : kExitOk;
}

}  // namespace

void add_demo_command(CLI::App& app, int* result) {
  auto args = std::make_shared<DemoArgs>();
  auto* cmd = app.add_subcommand("demo", vision_summary("demo"));
  cmd->add_option("--out", args->out, "Folder for datasets, poses, plots and the accuracy table")->capture_default_str();
  cmd->add_option("--seconds", args->seconds, "Seconds of each scenario to simulate")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  cmd->add_option("--scenario", args->scenarios,
                  "Scenario to run instead of paper-exp1 and swarm (repeatable): a built-in name (tetrapulse sim "
                  "--list) or a scenario YAML file");
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  cmd->footer("Scenarios: paper-exp1 and swarm unless --scenario is given (tetrapulse sim --list). Errors in mm and "
              "degrees.");
  cmd->callback([args, result] { *result = run_demo(*args, virtual_rig_simulation()); });
}

}  // namespace tetrapulse::cli
