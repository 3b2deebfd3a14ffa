#include "tetrapulse/sim/scene_builder.hpp"

#include <cmath>

#include "tetrapulse/sim/code_emitter.hpp"
#if TETRAPULSE_SIM_FIRMWARE_BOARDS
#include "tetrapulse/sim/firmware_board_emitter.hpp"
#endif
#include "tetrapulse/sim/noise_sampler.hpp"
#include "tetrapulse/sim/occluded_emitter.hpp"
#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {

std::unique_ptr<LedEmitter> contract_board_emitter(const Scenario& scenario, size_t index) {
  const TargetsFile& targets = scenario.targets;
  return std::make_unique<CodeEmitter>(targets.timebase, targets.modulation, targets.targets[index],
                                       BoardClock(scenario.simulation[index].clock));
}

BoardEmitterFactory default_board_emitter() {
#if TETRAPULSE_SIM_FIRMWARE_BOARDS
  return [](const Scenario& scenario, size_t index) { return firmware_board_emitter(scenario, index); };
#else
  return contract_board_emitter;
#endif
}

Scene build_scene(const Scenario& scenario, uint64_t seed, const BoardEmitterFactory& board) {
  Scene scene;
  scene.camera = LensProjector(scenario.camera);
  scene.camera_motion = Trajectory(scenario.camera_motion, stream_seed(seed, kStreamMotion, 0));
  scene.light_direction_W = scenario.light_direction_W;
  scene.ambient = scenario.ambient;
  uint64_t motion_index = 1;
  const TargetsFile& tf = scenario.targets;
  for (size_t k = 0; k < tf.targets.size(); ++k) {
    const Target& target = tf.targets[k];
    const TargetSimulation& sim = scenario.simulation[k];
    const int body = static_cast<int>(scene.bodies.size());
    scene.bodies.emplace_back(sim.motion, stream_seed(seed, kStreamMotion, motion_index++));
    const int emitter = static_cast<int>(scene.emitters.size());
    scene.emitters.push_back(std::make_unique<OccludedEmitter>(
        board(scenario, k), std::vector<TimeIntervals>(sim.occluded.begin(), sim.occluded.end())));
    SceneTarget st;
    st.id = target.id;
    st.body = body;
    for (int m = 0; m < 4; ++m) {
      LightSphere light;
      light.body = body;
      light.position_m = target.markers[static_cast<size_t>(m)].position_m;
      light.radius_m = target.marker_diameter_m / 2;
      light.radiance_e_per_ms = sim.radiance_e_per_ms;
      if (sim.radiance_spread > 0) {
        NoiseSampler spread(stream_seed(seed, kStreamBrightness, scene.lights.size()));
        light.radiance_e_per_ms *= std::exp(sim.radiance_spread * spread.normal());
      }
      light.beam_exponent = sim.beam_exponent;
      light.beam_axis_B = sim.beam_axis_B;
      light.rgb = sim.rgb;
      if (sim.paint_e_per_ms) {
        light.painted = true;
        light.paint_e_per_ms = *sim.paint_e_per_ms;
      }
      light.emitter = emitter;
      light.emitter_index = m;
      st.lights.push_back(static_cast<int>(scene.lights.size()));
      scene.lights.push_back(light);
    }
    scene.targets.push_back(st);
  }
  for (const Distractor& d : scenario.distractors) {
    LightSphere light;
    light.body = static_cast<int>(scene.bodies.size());
    scene.bodies.emplace_back(d.motion, stream_seed(seed, kStreamMotion, motion_index++));
    light.radius_m = d.diameter_m / 2;
    light.radiance_e_per_ms = d.radiance_e_per_ms;
    light.emitter = static_cast<int>(scene.emitters.size());
    scene.emitters.push_back(std::make_unique<FlickerEmitter>(d.flicker));
    scene.lights.push_back(light);
  }
  return scene;
}

}  // namespace tetrapulse::sim
