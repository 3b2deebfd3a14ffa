#pragma once
// A target seen by a camera, with a known pose, for the tests and benchmarks of
// identification and refinement. Frames and units as in pose.hpp.
#include <array>
#include <ostream>
#include <random>
#include <string>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {
// GoogleTest prints a camera parameter by its name.
inline void PrintTo(const CameraInfo& camera, std::ostream* os) { *os << camera.name; }
}  // namespace tetrapulse

namespace tetrapulse::testing {

// 752 x 480, about 100 degrees across, barrel distortion (plumb_bob).
CameraInfo wide_plumb_bob_camera();
// 752 x 480, about 200 degrees across (equidistant).
CameraInfo fisheye_camera();

// A target of hardware/targets/ (e.g. "paper-large.yaml"), read with the rig-dataset
// reader; the first target of the file.
Target hardware_target(const std::string& file);

// A random pose that puts every marker inside the image, `margin_px` from its border,
// and within 78 degrees of the optical axis, with the target origin at [near, far] m.
Pose random_visible_pose(std::mt19937_64& rng, const CameraModel& camera, const Target& target, double near,
                         double far, double margin_px);

// Marker centres' pixels under `pose`, each with isotropic Gaussian noise of
// `sigma_px` per axis.
std::array<Eigen::Vector2d, 4> observe(std::mt19937_64& rng, const CameraModel& camera, const Target& target,
                                       const Pose& pose, double sigma_px);

}  // namespace tetrapulse::testing
