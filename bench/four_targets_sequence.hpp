#pragma once
// The benchmarks' 240 frames of the four-targets scene (four_targets_scenario.hpp),
// rendered once per program, with each frame's exposure start (rig ns).
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "four_targets_scenario.hpp"
#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/random.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace tetrapulse::bench {

inline constexpr int kSequenceFrames = 240;

struct Sequence {
  sim::Scenario scenario;
  std::vector<cv::Mat> images;
  std::vector<int64_t> starts;
  int64_t exposure_ns = 0;
};

inline const Sequence& four_targets_sequence() {
  static const Sequence s = [] {
    Sequence q;
    q.scenario = *sim::parse_scenario(four_targets_scenario(), "bench");
    const sim::Scene scene = sim::build_scene(q.scenario, 1);
    sim::SensorModel sensor(q.scenario.camera.width, q.scenario.camera.height, q.scenario.sensor, 1);
    sim::FrameRenderer renderer(scene, q.scenario.render, sensor);
    q.exposure_ns = q.scenario.frames.exposure_ns;
    for (int k = 0; k < kSequenceFrames; ++k) {
      const int64_t start = q.scenario.frames.start_ns + k * q.scenario.frames.period_ns;
      cv::Mat image;
      renderer.render(start, q.exposure_ns, sim::stream_seed(1, sim::kStreamSensorNoise, uint64_t(k)), &image);
      q.images.push_back(image);
      q.starts.push_back(start);
    }
    return q;
  }();
  return s;
}

}  // namespace tetrapulse::bench
