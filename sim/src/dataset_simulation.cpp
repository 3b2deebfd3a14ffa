#include "tetrapulse/sim/dataset_simulation.hpp"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "tetrapulse/datasets/rig_dataset.hpp"
#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/random.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace tetrapulse::sim {

bool frame_dropped(const FrameSchedule& schedule, uint64_t seed, int64_t frame) {
  if (std::find(schedule.dropped.begin(), schedule.dropped.end(), frame) != schedule.dropped.end()) return true;
  if (schedule.drop_probability <= 0) return false;
  Random rng(stream_seed(seed, kStreamDroppedFrames, static_cast<uint64_t>(frame)));
  return rng.uniform() < schedule.drop_probability;
}

namespace {

// True when some marker of the target shows in the image at rig time t.
bool target_in_image(const Scene& scene, const SceneTarget& target, const Pose& T_CT) {
  for (int index : target.lights) {
    const LightSphere& light = scene.lights[static_cast<size_t>(index)];
    const Eigen::Vector3d c = T_CT.apply(light.position_m);
    Eigen::Vector2d px;
    if (!scene.camera.project(c, &px)) continue;
    const double radius_px = std::max(scene.camera.info().fx, scene.camera.info().fy) * light.radius_m / c.norm();
    if (scene.camera.in_image(px, -radius_px)) return true;
  }
  return false;
}

}  // namespace

DatasetResult<SimulationSummary> simulate_dataset(const Scenario& scenario, const SimulationOptions& options) {
  SimulationSummary summary;
  summary.seed = options.seed.value_or(scenario.seed);
  const FrameSchedule& fs = scenario.frames;
  const int64_t count = options.frames.value_or(options.ci ? fs.ci_count : fs.count);

  const Scene scene = build_scene(scenario, summary.seed, options.board);
  SensorModel sensor(scenario.camera.width, scenario.camera.height, scenario.sensor, summary.seed);
  FrameRenderer renderer(scene, scenario.render, sensor);

  auto writer = RigDatasetWriter::create(options.out, scenario.camera, scenario.targets);
  if (!writer) return tl::unexpected(writer.error());
  cv::Mat image;
  for (int64_t k = 0; k < count; ++k) {
    if (frame_dropped(fs, summary.seed, k)) {
      ++summary.frames_dropped;
      continue;
    }
    const int64_t t0 = fs.start_ns + k * fs.period_ns;
    renderer.render(t0, fs.exposure_ns, stream_seed(summary.seed, kStreamSensorNoise, static_cast<uint64_t>(k)), &image);
    if (auto r = writer->add_frame(k, t0, fs.exposure_ns, image); !r) return tl::unexpected(r.error());
    ++summary.frames_written;
    const double mid_s = (static_cast<double>(t0) + 0.5 * static_cast<double>(fs.exposure_ns)) * 1e-9;
    for (const SceneTarget& target : scene.targets) {
      const Pose T_CT = scene.body_in_camera(target.body, mid_s);
      if (!target_in_image(scene, target, T_CT)) continue;
      writer->add_groundtruth(GroundTruthRecord{k, target.id, PoseFields::from(T_CT)});
      ++summary.groundtruth_rows;
    }
  }
  if (auto r = writer->finish(); !r) return tl::unexpected(r.error());
  const std::string provenance = fmt::format("# Written by tetrapulse sim: scenario {}, seed {}, {} frame numbers.\n{}",
                                             scenario.name, summary.seed, count, scenario.source_text);
  if (auto r = write_text_file((std::filesystem::path(options.out) / "scenario.yaml").string(), provenance); !r) {
    return tl::unexpected(r.error());
  }
  return summary;
}

}  // namespace tetrapulse::sim
