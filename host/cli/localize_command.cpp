// tetrapulse localize: identified 6D poses from a rig dataset, a recorded video
// with its timestamps, or a live camera.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "live_localize.hpp"
#include "overlay_video.hpp"
#include "vision_commands.hpp"
#include "progress_bar.hpp"
#include "ros2_output.hpp"
#include "stop_signal.hpp"
#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/datasets/pose_writer.hpp"

namespace tetrapulse::cli {

namespace {

struct LocalizeArgs {
  std::string dataset;
  std::string out;
  std::string format = "csv";
  std::string p3p = "lambda";
  std::string prediction = "regression";
  int regression_poses = 2;
  bool centre_projection = false;
  int full_search_interval = 4;
  std::string video;
  std::string timestamps;
  std::string camera;
  int64_t exposure_ns = 2'000'000;
  std::string camera_info;
  std::string targets;
  bool quiet = false;
  std::string overlay;  // --overlay FILE: the frames with the poses drawn over them
  Ros2Args ros2;
  LiveArgs live;  // --camera aravis:ID | v4l2:DEV (live_localize.hpp)
};

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "tetrapulse localize: %s\n", message.c_str());
  return code;
}

PoseFormat format_of(const std::string& name) {
  if (name == "tum") return PoseFormat::kTum;
  if (name == "jsonl") return PoseFormat::kJsonLines;
  return PoseFormat::kCsv;
}

int run_localize(const LocalizeArgs& a) {
  const bool live = !a.camera.empty();
  if (a.dataset.empty() && (a.camera_info.empty() || a.targets.empty())) {
    return fail(kExitUsage, "give a DATASET folder (or --camera-info and --targets)");
  }
  if (a.out.empty() && !live) return fail(kExitUsage, "--out FILE is required (\"-\" for standard output)");
  if (!a.video.empty() && a.timestamps.empty()) return fail(kExitUsage, "--video needs --timestamps CSV");
  if (live && !a.video.empty()) return fail(kExitUsage, "--camera and --video exclude each other");

  // Calibration and targets: the dataset's, unless given.
  std::optional<RigDataset> dataset;
  CameraInfo camera;
  TargetsFile targets;
  const bool frames_from_dataset = a.video.empty() && !live;
  if (frames_from_dataset) {
    auto d = RigDataset::open(a.dataset);
    if (!d) return fail(kExitBadInput, d.error().what());
    dataset = std::move(*d);
    for (const DatasetError& line : dataset->skipped_lines()) {
      std::fprintf(stderr, "tetrapulse localize: skipped %s\n", line.what().c_str());
    }
    camera = dataset->camera();
    targets = dataset->targets();
  }
  const std::string folder = a.dataset.empty() ? "." : a.dataset;
  if (!a.camera_info.empty() || !frames_from_dataset) {
    auto c = read_camera_yaml(a.camera_info.empty() ? folder + "/camera.yaml" : a.camera_info);
    if (!c) return fail(kExitBadInput, c.error().what());
    camera = *c;
  }
  if (!a.targets.empty() || !frames_from_dataset) {
    auto t = read_targets_yaml(a.targets.empty() ? folder + "/targets.yaml" : a.targets);
    if (!t) return fail(kExitBadInput, t.error().what());
    targets = *t;
  }

  std::unique_ptr<FrameSource> source;
  if (frames_from_dataset) {
    source = dataset_frames(*dataset);
  } else if (!a.video.empty()) {
    auto s = video_frames(a.video, a.timestamps, camera);
    if (!s) return fail(kExitBadInput, s.error().what());
    source = std::move(*s);
  } else if (is_live_camera_spec(a.camera)) {
    LiveArgs live_args = a.live;
    live_args.camera = a.camera;
    auto s = live_frame_source(live_args, camera, targets, stop_on_signals());
    if (!s) return fail(kExitNoDevice, s.error());
    source = std::move(*s);
  } else {
    auto s = camera_frames(a.camera, camera, a.exposure_ns);
    if (!s) return fail(kExitNoDevice, s.error().what());
    source = std::move(*s);
  }

  LocalizerOptions options;
  options.p3p = a.p3p == "kneip" ? P3PSolver::kKneip : P3PSolver::kLambdaTwist;
  options.prediction.model =
      a.prediction == "kalman" ? PredictionModel::kConstantVelocity : PredictionModel::kLinearRegression;
  options.prediction.regression_poses = a.regression_poses;
  options.pose.sphere_centroid = !a.centre_projection;
  options.full_search_interval = a.full_search_interval;
  Localizer localizer(camera, targets, options);

  std::optional<Ros2Output> ros2;
  if (a.ros2.enabled) {
    auto r = Ros2Output::open(a.ros2, camera, targets, live);
    if (!r) return fail(kExitUsage, r.error());
    ros2 = std::move(*r);
    if (live_loop_state(*source)) {
      ros2->follow_live([&source] {
        const LiveLoopState l = *live_loop_state(*source);
        LiveFeed f;
        f.frames_matched = l.stats.match.matched;
        f.synchronised = l.stats.synchronised;
        f.counters.queue_drops = l.stats.queue_drops;
        f.counters.bad_buffers = l.stats.bad_buffers;
        f.counters.exposures_without_frame = l.stats.match.dropped;
        f.counters.frames_without_exposure = l.stats.match.unmatched_frames;
        f.monotonic_minus_rig_ns = l.monotonic_minus_rig_ns;
        return f;
      });
    }
  }
  std::optional<OverlayVideo> overlay;
  if (!a.overlay.empty()) {
    auto v = OverlayVideo::create(a.overlay, camera, targets);
    if (!v) return fail(kExitUsage, v.error().what());
    overlay = std::move(*v);
  }
  const PoseFormat format = format_of(a.format);
  std::optional<PoseWriter> writer;
  if (!a.out.empty()) {
    auto w = PoseWriter::open(a.out, format, targets);
    if (!w) return fail(kExitFailure, w.error().what());
    writer = std::move(*w);
  }
  const bool print = live && a.out != "-";  // a live camera prints poses as they come
  ProgressBar progress(source->count(), !a.quiet && !live);
  auto frame_began = std::chrono::steady_clock::now();
  const auto on_frame = [&](const Frame& f, const std::vector<TargetPose>& poses) -> DatasetResult<void> {
    if (ros2) {
      const auto took = std::chrono::steady_clock::now() - frame_began;
      ros2->frame(f, poses, std::chrono::duration_cast<std::chrono::nanoseconds>(took).count(), localizer);
    }
    for (const TargetPose& p : poses) {
      if (writer) {
        if (auto r = writer->write(f.frame, p); !r) return r;
      }
      if (print) {
        std::fputs(format_pose_line(format, f.frame, p).c_str(), stdout);
        std::fflush(stdout);
      }
    }
    if (overlay) {
      if (auto r = overlay->add(f, poses); !r) return r;
    }
    // Each frame reaches the file whole before the next is read: a stop or a crash
    // keeps every frame so far.
    if (writer) {
      if (auto r = writer->flush(); !r) return r;
    }
    progress.advance();
    frame_began = std::chrono::steady_clock::now();
    return {};
  };
  LocalizeHooks hooks;
  hooks.stop = &stop_on_signals();  // SIGINT, SIGTERM: stop after the frame in hand, close the file
  hooks.on_skip = [&](const Frame&, const DatasetError& why) {
    progress.finish();  // clears the bar's line for the message; advance() draws it again
    std::fprintf(stderr, "tetrapulse localize: skipped %s\n", why.what().c_str());
    progress.advance();
  };
  auto frames = localize_frames(*source, localizer, on_frame, hooks);
  progress.finish();
  if (overlay) {
    if (auto r = overlay->close(); !r) return fail(kExitFailure, r.error().what());
    if (!a.quiet) std::fprintf(stderr, "tetrapulse localize: overlay video: %zu frames written to %s\n", overlay->frames(), a.overlay.c_str());
  }
  if (!frames) return fail(kExitBadInput, frames.error().what());
  const size_t skipped = frames->skipped + (dataset ? dataset->skipped_lines().size() : 0);
  size_t rows = 0;
  if (writer) {
    rows = writer->rows();
    if (auto r = writer->close(); !r) return fail(kExitFailure, r.error().what());
  }
  if (!a.quiet && a.out != "-") {
    std::fprintf(stderr, "tetrapulse localize: %s%zu frames, %zu skipped, %zu poses%s%s\n",
                 frames->stopped ? "stopped by a signal after " : "", frames->frames, skipped, rows,
                 a.out.empty() ? "" : " written to ", a.out.c_str());
  }
  const bool published = !ros2 || ros2->finish(localizer, a.quiet);
  if (frames->frames + skipped > 0 && rows == 0 && writer) {
    return fail(kExitFailure, "no target was identified in any frame");
  }
  if (!published) return kExitPublishFailed;
  return skipped > 0 ? kExitSkipped : kExitOk;
}

}  // namespace

void add_localize_command(CLI::App& app, int* result) {
  auto args = std::make_shared<LocalizeArgs>();
  auto* cmd = app.add_subcommand("localize", vision_summary("localize"));
  cmd->add_option("dataset", args->dataset,
                  "Rig dataset folder (with --video or --camera: where camera.yaml and targets.yaml are)");
  cmd->add_option("--out", args->out, "Poses file to write (\"-\": standard output)");
  cmd->add_option("--format", args->format, "csv (poses.csv), tum (one trajectory per target) or jsonl")
      ->check(CLI::IsMember({"csv", "tum", "jsonl"}))
      ->capture_default_str();
  cmd->add_option("--p3p", args->p3p, "P3P solver: lambda (Lambda Twist) or kneip")
      ->check(CLI::IsMember({"lambda", "kneip"}))
      ->capture_default_str();
  cmd->add_option("--prediction", args->prediction, "Pose prediction: regression (k_R poses) or kalman")
      ->check(CLI::IsMember({"regression", "kalman"}))
      ->capture_default_str();
  cmd->add_option("--regression-poses", args->regression_poses, "k_R, poses in the linear regression")
      ->check(CLI::Range(1, PosePredictor::kMaxRegressionPoses))
      ->capture_default_str();
  cmd->add_flag("--centre-projection", args->centre_projection,
                "Model blob centroids as the projections of marker centres (default: sphere images)");
  cmd->add_option("--full-search-interval", args->full_search_interval,
                  "Frames between whole-image searches while something is not tracked")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--video", args->video, "A recorded video (frames in order of --timestamps)");
  cmd->add_option("--timestamps", args->timestamps, "CSV frame,timestamp_ns,exposure_ns for --video");
  cmd->add_option("--camera", args->camera, "A live camera: aravis:ID (IP address or device id), v4l2:/dev/videoN, or /dev/videoN through OpenCV; prints poses as they come");
  cmd->add_option("--exposure-ns", args->exposure_ns, "Exposure of the live camera (ns)")
      ->check(CLI::Range(int64_t{1}, int64_t{10'000'000'000}))
      ->capture_default_str();
  cmd->add_option("--camera-info", args->camera_info, "camera.yaml to use (default: DATASET/camera.yaml)");
  cmd->add_option("--targets", args->targets, "targets.yaml to use (default: DATASET/targets.yaml)");
  cmd->add_flag("--quiet", args->quiet, "No progress bar or summary");
  cmd->add_option("--overlay", args->overlay,
                  "Also write a video (.avi, .mp4, .mkv) of the frames with markers, target axes and ids drawn over them");
  add_ros2_options(cmd, &args->ros2);
  add_live_options(cmd, &args->live);
  cmd->add_option("--record", args->live.record, "With --camera aravis:|v4l2:, also record the frames as a rig dataset");
  cmd->footer("Dataset format and poses.csv: docs/rig-dataset.md.");
  cmd->callback([args, result] { *result = run_localize(*args); });
}

}  // namespace tetrapulse::cli
