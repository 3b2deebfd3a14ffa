// Blob extraction and tracking speed on one core, against the localizer's
// budget (2 ms a frame from scratch, 0.3 ms while tracking): whole-frame
// extraction of a 752x480 frame with 16 markers <= ~1 ms, 16 ROIs of about
// 20 x 20 px <= ~0.1 ms.
#include <benchmark/benchmark.h>

#include <random>

#include <opencv2/core.hpp>

#include "spot_renderer.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"

namespace tetrapulse {
namespace {

constexpr int kWidth = 752, kHeight = 480, kMarkers = 16;

// 16 spots (sigma 1.2..2 px) on a background of 30 with read noise 3 (8-bit
// scale), `scale` times brighter for 16 bits; `dark` draws them below it.
struct Scene {
  cv::Mat image;
  std::vector<Eigen::Vector2d> markers;
};

Scene make_scene(int depth, bool dark) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(30, kWidth - 30), uy(30, kHeight - 30), us(1.2, 2.0);
  const double scale = depth == CV_16U ? 256.0 : 1.0;
  Scene s;
  cv::Mat1d img(kHeight, kWidth, (dark ? 220.0 : 30.0) * scale);
  while (s.markers.size() < size_t(kMarkers)) {
    const Eigen::Vector2d c(ux(rng), uy(rng));
    bool apart = true;
    for (const auto& m : s.markers) apart = apart && (m - c).norm() > 30;
    if (!apart) continue;
    s.markers.push_back(c);
    test::add_gaussian(&img, c, us(rng), (dark ? -170.0 : 170.0) * scale);
  }
  test::add_noise(&img, 3.0 * scale, 3);
  s.image = test::quantise(img, depth);
  return s;
}

void whole_frame(benchmark::State& state, int depth, bool dark) {
  const Scene scene = make_scene(depth, dark);
  BlobExtractorConfig config;
  config.polarity = dark ? MarkerPolarity::kDark : MarkerPolarity::kLight;
  BlobExtractor extractor(config);
  BlobExtraction out;
  for (auto _ : state) {
    const auto ok = extractor.extract(scene.image, kMarkers, &out);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(out.blobs.data());
  }
  state.counters["blobs"] = double(out.blobs.size());  // must read 16
}

void BM_WholeFrame_8bit(benchmark::State& state) { whole_frame(state, CV_8U, false); }
void BM_WholeFrame_16bit(benchmark::State& state) { whole_frame(state, CV_16U, false); }
void BM_WholeFrame_8bit_Dark(benchmark::State& state) { whole_frame(state, CV_8U, true); }

// 16 ROIs at the markers, predicted 1.5 px off: radius 6 + aperture 4 gives
// 21 x 21 px windows. Range(1) = 1: every other marker is in a 0 bit (absent).
void BM_Rois_8bit(benchmark::State& state) {
  Scene scene = make_scene(CV_8U, false);
  const bool half_off = state.range(0) == 1;
  if (half_off) {
    cv::Mat1d img(kHeight, kWidth, 30.0);
    for (size_t i = 0; i < scene.markers.size(); i += 2) test::add_gaussian(&img, scene.markers[i], 1.6, 170);
    test::add_noise(&img, 3.0, 3);
    scene.image = test::quantise(img, CV_8U);
  }
  std::vector<BlobRoi> rois;
  for (size_t i = 0; i < scene.markers.size(); ++i) {
    BlobRoi r;
    r.center = scene.markers[i] + Eigen::Vector2d(1.5, -1.0);
    r.radius = 6;
    r.aperture_radius = 4;
    r.tag = int64_t(i);
    rois.push_back(r);
  }
  BlobExtractor extractor;
  BlobExtraction out;
  for (auto _ : state) {
    const auto ok = extractor.extract(scene.image, rois, &out);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(out.rois.data());
  }
  int detected = 0;
  for (const auto& m : out.rois) detected += m.detected();
  state.counters["detected"] = detected;  // 16, or 8 with half the markers off
}

// One tracker update with 16 tracks and 16 blobs (whole-frame association).
void BM_TrackerUpdate(benchmark::State& state) {
  const Scene scene = make_scene(CV_8U, false);
  BlobExtraction frame;
  for (const auto& m : scene.markers) {
    Blob b;
    b.centroid = m;
    b.intensity = 1000;
    frame.blobs.push_back(b);
  }
  BlobTracker tracker;
  int64_t k = 0;
  for (auto _ : state) {
    for (auto& b : frame.blobs) b.centroid.x() += 0.5;
    tracker.update(ExposureStamp{k, k * 10'000'000, 2'000'000}, frame);
    ++k;
  }
  state.counters["tracks"] = double(tracker.tracks().size());  // must read 16
}

BENCHMARK(BM_WholeFrame_8bit)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WholeFrame_16bit)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WholeFrame_8bit_Dark)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Rois_8bit)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TrackerUpdate)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tetrapulse

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // one core, as on the robot's budget
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
