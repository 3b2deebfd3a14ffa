#include "tetrapulse/localizer/testing/target_views.hpp"

#include <stdexcept>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/localizer/testing/p3p_problems.hpp"

namespace tetrapulse::testing {

CameraInfo wide_plumb_bob_camera() {
  // k1..k3 keep the radial distortion monotonic over the whole sensor.
  return CameraInfo{"wide_plumb_bob", 752, 480, 376.0, 376.5, 375.6, 240.3, DistortionModel::kPlumbBob,
                    {-0.2, 0.05, 0.0011, -0.0007, 0.0}};
}

CameraInfo fisheye_camera() {
  return CameraInfo{"fisheye", 752, 480, 210.0, 210.4, 376.2, 239.4, DistortionModel::kEquidistant,
                    {0.02, -0.01, 0.003, -0.0005, 0.0}};
}

Target hardware_target(const std::string& file) {
  const std::string path = std::string(TETRAPULSE_SOURCE_DIR) + "/hardware/targets/" + file;
  const auto targets = read_targets_yaml(path);
  if (!targets || targets->targets.empty()) {
    throw std::runtime_error(targets ? path + ": no target" : targets.error().what());
  }
  return targets->targets.front();
}

Pose random_visible_pose(std::mt19937_64& rng, const CameraModel& camera, const Target& target, double near,
                         double far, double margin_px) {
  std::uniform_real_distribution<double> u(0, 1);
  for (;;) {
    const Eigen::Vector2d px{u(rng) * (camera.width() - 1), u(rng) * (camera.height() - 1)};
    Eigen::Vector3d bearing;
    if (!camera.unproject(px, &bearing)) continue;
    const Pose pose{random_rotation(rng), (near + (far - near) * u(rng)) * bearing};
    bool visible = true;
    for (const Marker& m : target.markers) {
      // Inside the image, within the lens model's field (the pixel maps back to the
      // point's ray), and within 78 degrees of the axis, so that a perturbed pose
      // still has every marker at z > 0 where CameraModel projects.
      const Eigen::Vector3d p_C = pose.apply(m.position_m);
      visible = visible && p_C.z() > 0.2 * p_C.norm();
      Eigen::Vector2d p;
      Eigen::Vector3d back;
      visible = visible && camera.project(p_C, &p) && camera.in_image(p, margin_px) && camera.unproject(p, &back) &&
                back.cross(p_C.normalized()).norm() < 1e-9;
    }
    if (visible) return pose;
  }
}

std::array<Eigen::Vector2d, 4> observe(std::mt19937_64& rng, const CameraModel& camera, const Target& target,
                                       const Pose& pose, double sigma_px) {
  std::normal_distribution<double> noise(0.0, sigma_px);
  std::array<Eigen::Vector2d, 4> px;
  for (int i = 0; i < 4; ++i) {
    camera.project(pose.apply(target.markers[i].position_m), &px[i]);
    if (sigma_px > 0) px[i] += Eigen::Vector2d{noise(rng), noise(rng)};
  }
  return px;
}

}  // namespace tetrapulse::testing
