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
#include "four_targets_scenario.hpp"

namespace {

using namespace tetrapulse::sim;

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
  static Rig r(*parse_scenario(tetrapulse::bench::four_targets_scenario(), "bench"));
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
  // The settings of RigDatasetWriter::add_frame (datasets/src/rig_dataset.cpp).
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
