#pragma once
// What the virtual camera looks at: a camera and bodies moving through the world
// frame W (motion.hpp), and glowing spheres fixed on those bodies, each lit by an
// emitter. Markers are spheres on target bodies; distractor lamps are spheres on
// bodies of their own. Metres, rig time; camera frame as in OpenCV.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/sim/lens_projector.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/sim/led_emitter.hpp"
#include "tetrapulse/sim/motion.hpp"

namespace tetrapulse::sim {

struct LightSphere {
  int body = 0;                                          // index into Scene::bodies
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // centre, body frame
  double radius_m = 0;
  double radiance_e_per_ms = 0;  // electrons per fully covered pixel per ms of exposure at full emission
  int emitter = 0;               // index into Scene::emitters
  double beam_exponent = 0;      // radiance x cos(view angle off beam_axis_B)^beam_exponent (0: uniform)
  Eigen::Vector3d beam_axis_B = Eigen::Vector3d::UnitZ();  // body frame, unit
  int emitter_index = 0;         // which light of that emitter (a marker's index 0..3)
  // A painted ball (a passive marker) instead of a light: it reflects the scene's
  // light (Scene::light_direction_W; Lambertian, Scene::ambient of it on the shadowed
  // side) and hides the background behind it. paint_e_per_ms: electrons per fully
  // covered pixel per ms where its surface faces the light squarely. The emitter
  // only says when it is hidden (a constant one: never); radiance and beam are unused.
  bool painted = false;
  double paint_e_per_ms = 0;
  // Its colour: the share of its light in the R, G and B channels of a Bayer sensor
  // (a grey sensor takes their mean); white (1 1 1) by default.
  Eigen::Vector3d rgb = Eigen::Vector3d::Ones();
};

// A target: a body carrying four markers, named by the id it has in targets.yaml.
struct SceneTarget {
  int id = 0;
  int body = 0;
  std::vector<int> lights;  // its markers, indices into Scene::lights
};

struct Scene {
  LensProjector camera{CameraInfo{}};
  Trajectory camera_motion;
  std::vector<Trajectory> bodies;
  std::vector<std::unique_ptr<LedEmitter>> emitters;
  std::vector<LightSphere> lights;
  std::vector<SceneTarget> targets;
  // The light painted balls reflect: a distant source in this direction (world
  // frame, unit, pointing to the light) and the share of it that reaches their
  // shadowed side (sky, walls, [0, 1]).
  Eigen::Vector3d light_direction_W = Eigen::Vector3d::UnitZ();
  double ambient = 0.3;

  // Pose of body `body` in the camera frame at rig time t (seconds): p_C = R p_B + t.
  Pose body_in_camera(int body, double t_s) const {
    return camera_motion.at(t_s).inverse() * bodies[static_cast<size_t>(body)].at(t_s);
  }
};

}  // namespace tetrapulse::sim
