// How fast the virtual rig renders: one 752x480 frame with four large targets
// (16 markers of 3 cm at 0.7 to 1.9 m, moving), on one thread.
//   BM_RenderFrame:          the lights, then the sensor (background, noise, quantisation)
//   BM_RenderFrameAndEncode: the same plus PNG encoding with the dataset writer's settings
//   BM_Light / BM_Sensor:    the two halves of BM_RenderFrame
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/random.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace {

using namespace tetrapulse::sim;

std::string target_yaml(int id, const char* codes[4], double x, double y, double yaw_deg) {
  const char* positions[4] = {"[0.0, -0.1651, 0.2366]", "[0.0, 0.1304, 0.1845]", "[0.0626, -0.0221, 0.0539]",
                              "[-0.0802, 0.0249, 0.0621]"};
  std::string t = "  - id: " + std::to_string(id) + "\n    marker_diameter_m: 0.03\n    radiance_e_per_ms: 1600\n"
                  "    markers:\n";
  for (int m = 0; m < 4; ++m) {
    t += std::string("      - position_m: ") + positions[m] + "\n        code: \"" + codes[m] + "\"\n";
  }
  t += "    motion: {kind: circle, center_m: [" + std::to_string(x) + ", " + std::to_string(y) +
       ", 0.0], radius_m: 0.1, period_s: 6, rpy_deg: [0, 0, " + std::to_string(yaw_deg) + "]}\n";
  return t;
}

const std::string& bench_scenario() {
  static const std::string text = [] {
    const char* codes[4][4] = {{"010011100101", "011001001001", "100111110010", "010010010110"},
                               {"100110101100", "101101010110", "100101100110", "011100101010"},
                               {"110110010010", "001011110101", "100101010011", "101011001110"},
                               {"011001100110", "010110100111", "101010010110", "100110111001"}};
    std::string s = R"(name: bench-four-targets
frames: {start_ns: 4000000, period_ns: 10000000, exposure_ns: 2000000, count: 100000}
camera:
  image_width: 752
  image_height: 480
  hfov_deg: 90
  distortion_model: plumb_bob
  distortion_coefficients: [-0.05, 0.01, 0.0, 0.0, 0.0]
  psf_sigma_px: 0.6
  motion:
    kind: smooth_random
    position_m: [0.0, 0.0, 1.6]
    rpy_deg: [180, 0, 0]
    amplitude_m: [0.1, 0.1, 0.3]
    rotation_amplitude_deg: [5, 5, 30]
    min_period_s: 2.5
timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 10000000}
modulation: {kind: two_level, low: 0.3}
targets:
)";
    s += target_yaml(1, codes[0], -0.35, -0.2, 0);
    s += target_yaml(2, codes[1], 0.35, -0.2, 90);
    s += target_yaml(3, codes[2], -0.35, 0.25, 180);
    s += target_yaml(4, codes[3], 0.35, 0.25, 270);
    return s;
  }();
  return text;
}

struct Rig {
  Scenario scenario;
  Scene scene;
  SensorModel sensor;
  FrameRenderer renderer;
  explicit Rig(Scenario s)
      : scenario(std::move(s)),
        scene(build_scene(scenario, 1)),
        sensor(scenario.camera.width, scenario.camera.height, scenario.sensor, 1),
        renderer(scene, scenario.render, sensor) {}
  int64_t t0(int64_t k) const { return scenario.frames.start_ns + k * scenario.frames.period_ns; }
};

Rig& rig() {
  static Rig r(*parse_scenario(bench_scenario(), "bench"));
  return r;
}

void BM_RenderFrame(benchmark::State& state) {
  cv::setNumThreads(1);
  Rig& r = rig();
  cv::Mat image;
  int64_t k = 0;
  for (auto _ : state) {
    r.renderer.render(r.t0(k), r.scenario.frames.exposure_ns, stream_seed(1, kStreamSensorNoise, k), &image);
    benchmark::DoNotOptimize(image.data);
    ++k;
  }
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)->Unit(benchmark::kMillisecond);

void BM_RenderFrameAndEncode(benchmark::State& state) {
  cv::setNumThreads(1);
  Rig& r = rig();
  cv::Mat image;
  std::vector<uchar> png;
  // The settings of RigDatasetWriter::add_frame (localizer/src/rig_dataset.cpp).
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE};
  int64_t k = 0;
  for (auto _ : state) {
    r.renderer.render(r.t0(k), r.scenario.frames.exposure_ns, stream_seed(1, kStreamSensorNoise, k), &image);
    cv::imencode(".png", image, png, params);
    benchmark::DoNotOptimize(png.data());
    ++k;
  }
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["png_bytes"] = static_cast<double>(png.size());
}
BENCHMARK(BM_RenderFrameAndEncode)->Unit(benchmark::kMillisecond);

void BM_Light(benchmark::State& state) {
  Rig& r = rig();
  cv::Mat light(r.scenario.camera.height, r.scenario.camera.width, CV_32F);
  int64_t k = 0;
  for (auto _ : state) {
    light.setTo(0);
    r.renderer.add_light(r.t0(k), r.scenario.frames.exposure_ns, &light);
    benchmark::DoNotOptimize(light.data);
    ++k;
  }
}
BENCHMARK(BM_Light)->Unit(benchmark::kMillisecond);

void BM_Sensor(benchmark::State& state) {
  Rig& r = rig();
  cv::Mat light(r.scenario.camera.height, r.scenario.camera.width, CV_32F, cv::Scalar(0));
  r.renderer.add_light(r.t0(0), r.scenario.frames.exposure_ns, &light);
  cv::Mat image;
  uint64_t k = 0;
  for (auto _ : state) {
    r.sensor.expose(light, r.scenario.frames.exposure_ns, stream_seed(1, kStreamSensorNoise, k++), &image);
    benchmark::DoNotOptimize(image.data);
  }
}
BENCHMARK(BM_Sensor)->Unit(benchmark::kMillisecond);

}  // namespace
