// tetrapulse record: a rig dataset (docs/rig-dataset.md) from a live camera, with
// the given camera.yaml and targets.yaml and frames.csv from the matched exposure
// stamps. SIGINT/SIGTERM or --frames N end it with a complete, valid dataset.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "live_capture.hpp"
#include "stop_signal.hpp"
#include "vision_commands.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace tetrapulse::cli {
namespace {

struct RecordArgs {
  LiveArgs live;
  std::string camera_info;
  std::string targets;
  std::string out;
  bool quiet = false;
};

constexpr uint64_t kNamedBadFrames = 5;

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "tetrapulse record: %s\n", message.c_str());
  return code;
}

int run_record(RecordArgs a) {
  auto camera = read_camera_yaml(a.camera_info);
  if (!camera) return fail(kExitBadInput, camera.error().what());
  auto targets = read_targets_yaml(a.targets);
  if (!targets) return fail(kExitBadInput, targets.error().what());
  auto writer = RigDatasetWriter::create(a.out, *camera, *targets);
  if (!writer) return fail(kExitFailure, writer.error().what());
  a.live.queue = std::max(a.live.queue, 64);  // a recorder rides out slow PNG writes
  auto live = LiveCapture::open(a.live, camera->width, camera->height,
                                [](const std::string& n) { std::fprintf(stderr, "tetrapulse record: %s\n", n.c_str()); });
  if (!live) return fail(kExitNoDevice, live.error());
  const bool progress = !a.quiet && isatty(STDERR_FILENO);
  const std::atomic<bool>& stop = stop_on_signals();
  int64_t written = 0;
  uint64_t skipped = 0;
  while (auto f = (*live)->next(stop)) {
    if (f->frame.bad) {
      // Named one by one at first; on a lossy link the summary counts the rest.
      if (++skipped <= kNamedBadFrames) {
        std::fprintf(stderr, "%stetrapulse record: skipped %s%s\n", progress ? "\r\033[K" : "", f->frame.bad->c_str(),
                     skipped == kNamedBadFrames ? " (further ones only counted)" : "");
      }
      continue;
    }
    if (f->frame.image.cols != camera->width || f->frame.image.rows != camera->height) {
      ++skipped;
      std::fprintf(stderr, "%stetrapulse record: skipped %s frame %llu: %dx%d image, camera.yaml says %dx%d\n",
                   progress ? "\r\033[K" : "", (*live)->camera_name().c_str(),
                   static_cast<unsigned long long>(f->frame.sequence), f->frame.image.cols, f->frame.image.rows,
                   camera->width, camera->height);
      continue;
    }
    const host::Exposure& e = f->stamp.exposure;
    if (auto r = writer->add_frame(e.frame, e.timestamp_ns, e.exposure_ns, f->frame.image); !r) {
      return fail(kExitFailure, r.error().what());
    }
    ++written;
    if (progress) {
      const LiveStats s = (*live)->stats();
      std::fprintf(stderr, "\r\033[Ktetrapulse record: %lld frames%s, %llu bad, %llu dropped", static_cast<long long>(written),
                   a.live.frames > 0 ? fmt::format(" of {}", a.live.frames).c_str() : "",
                   static_cast<unsigned long long>(s.bad_buffers), static_cast<unsigned long long>(s.queue_drops + s.match.dropped));
    }
  }
  const bool stopped = stop;
  const auto error = (*live)->error();
  const LiveStats s = (*live)->stats();
  const std::string transport = (*live)->transport_summary();
  live->reset();  // the camera stops before the files are finished
  if (auto r = writer->finish(); !r) return fail(kExitFailure, r.error().what());
  if (progress) std::fputs("\r\033[K", stderr);
  if (!a.quiet) {
    std::fprintf(stderr,
                 "tetrapulse record: %s%lld frames written to %s; %llu buffers, %llu bad, %llu dropped by the queue, "
                 "%llu exposures without a frame, %llu frames without an exposure, %llu skipped; stamps: %s\n",
                 stopped ? "stopped by a signal after " : "", static_cast<long long>(written), a.out.c_str(),
                 static_cast<unsigned long long>(s.grabbed), static_cast<unsigned long long>(s.bad_buffers),
                 static_cast<unsigned long long>(s.queue_drops), static_cast<unsigned long long>(s.match.dropped),
                 static_cast<unsigned long long>(s.match.unmatched_frames), static_cast<unsigned long long>(skipped),
                 stamp_source(s).c_str());
    if (!transport.empty()) std::fprintf(stderr, "tetrapulse record: %s\n", transport.c_str());
  }
  if (error && !stopped && (a.live.frames == 0 || written < a.live.frames)) return fail(kExitDeviceError, *error);
  return skipped > 0 ? kExitSkipped : kExitOk;
}

}  // namespace

void add_record_command(CLI::App& app, int* result) {
  auto args = std::make_shared<RecordArgs>();
  auto* cmd = app.add_subcommand("record", vision_summary("record"));
  cmd->add_option("--camera", args->live.camera, "aravis:ID (IP address or device id) or v4l2:/dev/videoN")->required();
  cmd->add_option("--camera-info", args->camera_info, "camera.yaml (calibration; its size is set on the camera)")->required();
  cmd->add_option("--targets", args->targets, "targets.yaml")->required();
  cmd->add_option("--out", args->out, "Dataset folder to write")->required();
  cmd->add_flag("--quiet", args->quiet, "No progress line or summary");
  add_live_options(cmd, &args->live);
  cmd->footer("Dataset format: docs/rig-dataset.md. SIGINT or --frames N ends the recording with a valid dataset.");
  cmd->callback([args, result] { *result = run_record(*args); });
}

}  // namespace tetrapulse::cli
