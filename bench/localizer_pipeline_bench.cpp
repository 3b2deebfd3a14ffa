// The whole localizer per frame, next to the AprilTag 3 detector, on 752x480
// frames of the same scene size. One thread (cv::setNumThreads(1), AprilTag
// nthreads = 1).
//   BM_LocalizerFullFrame:  every frame searched whole (blobs over the image,
//                           tracks, bits, pose of the 4 tracked targets); a
//                           fifth target that is never in view keeps the
//                           whole-image search going every frame, as while a
//                           target is missing.
//   BM_LocalizerAcquisition: a fresh localizer over its first 12 frames (whole
//                           image searches, identification of all four targets).
//   BM_LocalizerTracking:   the four targets tracked (ROIs only), per frame.
//   BM_Localizer*Sequence:  the same two, over frames 30-239 once (for
//                           instruction counts: the same frames every run).
//   BM_AprilTag36h11/D:     apriltag_detector_detect with quad_decimate D on a
//                           frame showing one tag36h11 whose black square is
//                           0.30 m, the span of the paper's large target, 1.5 m
//                           away and tilted 20 degrees.
// Frames come from the virtual rig (four_targets_scenario.hpp), rendered once.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "four_targets_sequence.hpp"
#include "localizer_frame_timing.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace {

using namespace tetrapulse;

using bench::Sequence;
const Sequence& sequence() { return bench::four_targets_sequence(); }

// Times one frame per iteration from frame `warm_up` on (localizer_frame_timing.hpp).
void time_frames(benchmark::State& state, const TargetsFile& targets, const LocalizerOptions& options, int warm_up) {
  bench::time_frames(state, sequence(), targets, options, warm_up);
}

// Full frame: the scene's targets and one that never shows, searched for every frame.
TargetsFile with_absent_target() {
  TargetsFile targets = sequence().scenario.targets;
  Target absent = targets.targets[0];
  absent.id = 99;
  for (Marker& m : absent.markers) m.code = parse_code("000111010110", nullptr);
  targets.targets.push_back(absent);
  return targets;
}

LocalizerOptions searching_every_frame() {
  LocalizerOptions options;
  options.full_search_interval = 1;
  return options;
}

void BM_LocalizerFullFrame(benchmark::State& state) {
  time_frames(state, with_absent_target(), searching_every_frame(), 30);
}
BENCHMARK(BM_LocalizerFullFrame)->Unit(benchmark::kMicrosecond);

void BM_LocalizerTracking(benchmark::State& state) { time_frames(state, sequence().scenario.targets, {}, 30); }
BENCHMARK(BM_LocalizerTracking)->Unit(benchmark::kMicrosecond);

// Frames 30 to 239 once, after 30 untimed ones: the same frames every run, for
// instruction counts (callgrind --toggle-collect='*sequence_frames*' counts
// these calls only). Not inlined, so that callgrind can name it.
[[gnu::noinline]] void sequence_frames(Localizer* localizer, const Sequence& s, int from) {
  bench::feed(localizer, s, from, int(s.images.size()));
}

void whole_sequence(benchmark::State& state, const TargetsFile& targets, const LocalizerOptions& options) {
  bench::time_sequence(state, sequence(), targets, options, 30, sequence_frames);
}

void BM_LocalizerFullFrameSequence(benchmark::State& state) {
  whole_sequence(state, with_absent_target(), searching_every_frame());
}
BENCHMARK(BM_LocalizerFullFrameSequence)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_LocalizerTrackingSequence(benchmark::State& state) { whole_sequence(state, sequence().scenario.targets, {}); }
BENCHMARK(BM_LocalizerTrackingSequence)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_LocalizerAcquisition(benchmark::State& state) {
  cv::setNumThreads(1);
  const Sequence& s = sequence();
  constexpr int kAcquisitionFrames = 12;
  int64_t identified = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto localizer = std::make_unique<Localizer>(s.scenario.camera, s.scenario.targets);
    state.ResumeTiming();
    for (int k = 0; k < kAcquisitionFrames; ++k) {
      auto out = localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
      if (k == kAcquisitionFrames - 1 && out) identified += int64_t(out->size());
    }
  }
  state.counters["per_frame_us"] =
      benchmark::Counter(double(kAcquisitionFrames) * 1e-6, benchmark::Counter::kIsIterationInvariantRate |
                                                                 benchmark::Counter::kInvert);
  state.counters["identified_by_frame_12"] = double(identified) / double(state.iterations());
}
BENCHMARK(BM_LocalizerAcquisition)->Unit(benchmark::kMicrosecond);

// A 752x480 frame like the rig's (dark textured background, noise) with one
// tag36h11 (id 7) drawn in through the camera: black square 0.30 m, 1.5 m away.
cv::Mat apriltag_frame(apriltag_family_t* family) {
  const Sequence& s = sequence();
  const CameraInfo& cam = s.scenario.camera;
  image_u8_t* tag = apriltag_to_image(family, 7);  // total_width cells, border cells white
  const int cells = tag->width;
  cv::Mat tag_image(tag->height, tag->width, CV_8UC1);
  for (int y = 0; y < tag->height; ++y)
    for (int x = 0; x < tag->width; ++x) tag_image.at<uint8_t>(y, x) = tag->buf[y * tag->stride + x];
  // image_u8_destroy is not exported by Debian's libapriltag; it frees the two blocks.
  std::free(tag->buf);
  std::free(tag);
  // Pixel corners of the tag image in the target plane: the black square spans
  // cells [1, cells - 1) and is 0.30 m wide.
  const double cell_m = 0.30 / double(family->width_at_border);
  const double half = 0.5 * cells * cell_m;
  const cv::Matx33d R = cv::Matx33d(1, 0, 0, 0, std::cos(0.35), -std::sin(0.35), 0, std::sin(0.35), std::cos(0.35));
  const cv::Vec3d t(0.1, -0.05, 1.5);
  std::vector<cv::Point3d> corners = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  std::vector<cv::Point2f> image_corners;
  const cv::Matx33d K(cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
  for (const cv::Point3d& c : corners) {
    const cv::Vec3d p = R * cv::Vec3d(c.x, c.y, c.z) + t;
    const cv::Vec3d q = K * p;
    image_corners.emplace_back(float(q[0] / q[2]), float(q[1] / q[2]));
  }
  const std::vector<cv::Point2f> source = {{0, 0}, {float(cells), 0}, {float(cells), float(cells)}, {0, float(cells)}};
  const cv::Mat H = cv::getPerspectiveTransform(source, image_corners);
  cv::Mat frame = s.images[0].clone();
  cv::Mat warped(frame.size(), CV_8UC1), mask(frame.size(), CV_8UC1, cv::Scalar(0));
  cv::Mat lit;
  tag_image.convertTo(lit, CV_8U, 150.0 / 255.0, 20);  // a lit tag: black 20, white 170
  cv::warpPerspective(lit, warped, H, frame.size(), cv::INTER_LINEAR);
  cv::warpPerspective(cv::Mat(tag_image.size(), CV_8UC1, cv::Scalar(255)), mask, H, frame.size(), cv::INTER_NEAREST);
  warped.copyTo(frame, mask);
  cv::Mat noise(frame.size(), CV_16SC1);
  cv::randn(noise, 0, 3);
  cv::Mat noisy;
  frame.convertTo(noisy, CV_16S);
  noisy += noise;
  noisy.convertTo(frame, CV_8U);
  return frame;
}

void BM_AprilTag36h11(benchmark::State& state) {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  apriltag_detector_add_family(detector, family);
  detector->nthreads = 1;
  detector->quad_decimate = float(state.range(0));
  cv::Mat frame = apriltag_frame(family);
  image_u8_t image{frame.cols, frame.rows, int(frame.step), frame.data};
  int64_t found = 0;
  for (auto _ : state) {
    zarray_t* detections = apriltag_detector_detect(detector, &image);
    found += zarray_size(detections);
    apriltag_detections_destroy(detections);
  }
  state.counters["tags_per_frame"] = double(found) / double(state.iterations());
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
}
BENCHMARK(BM_AprilTag36h11)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
