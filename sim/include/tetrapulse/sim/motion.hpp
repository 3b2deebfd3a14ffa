#pragma once
// How a body (the camera or a target) moves: its pose in the world frame W as a
// function of rig time. W is any right-handed frame in metres; the built-in
// scenarios put z up and the floor at z = 0. A pose (R, t) of body B maps body
// coordinates to world coordinates, p_W = R p_B + t; for the camera, B is the
// OpenCV camera frame (x right, y down, z forward).
// Orientations in scenarios are rpy = [roll, pitch, yaw] (radians here, degrees in
// files) with R = Rz(yaw) Ry(pitch) Rx(roll).
#include <cstdint>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/pose.hpp"

namespace tetrapulse::sim {

Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy_rad);

struct StaticMotion {
  Pose pose;
};

struct Waypoint {
  double t_s = 0;  // rig time, seconds; strictly increasing along the list
  Pose pose;
};

// Piecewise linear in position, spherical-linear in orientation; holds the end
// poses outside the listed times, or repeats the whole list when `loop`.
struct WaypointMotion {
  std::vector<Waypoint> points;  // at least one
  bool loop = false;
};

// A smooth band-limited wander about `centre`: each of the three position axes and
// the three body-frame rotation axes is a sum of sinusoids with seeded random
// frequencies (periods between min_period_s and 8 min_period_s), phases and weights
// summing to 1, so that axis i stays within +-amplitude_m[i] (or +-rotation_amplitude_rad[i]):
//   t(t) = centre.t + diag(amplitude_m) s(t),   R(t) = centre.R Exp(diag(rotation_amplitude_rad) r(t)).
// A hovering vehicle is the same with small amplitudes.
struct SmoothRandomMotion {
  Pose centre;
  Eigen::Vector3d amplitude_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_amplitude_rad = Eigen::Vector3d::Zero();
  double min_period_s = 1.0;
};

// Uniform motion on a circle of radius_m about center_m in the plane normal to
// `axis`: angle phi(t) = phase_rad + 2 pi t / period_s (right-handed about axis).
// Orientation: `orientation`, turned with phi about `axis` when follow_tangent
// (a robot that keeps its heading along the path).
struct CircleMotion {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  double radius_m = 0;
  double period_s = 1;
  double phase_rad = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  bool follow_tangent = true;
};

using MotionSpec = std::variant<StaticMotion, WaypointMotion, SmoothRandomMotion, CircleMotion>;

class Trajectory {
 public:
  Trajectory() : spec_(StaticMotion{}) {}
  // `seed` draws the smooth random motion's sinusoids (unused by the other kinds).
  Trajectory(MotionSpec spec, uint64_t seed);

  // Pose of the body in W at rig time t (seconds).
  Pose at(double t_s) const;

 private:
  struct Harmonic {
    double weight, frequency_hz, phase_rad;
  };
  static constexpr int kHarmonics = 4;
  // Channel c (0..2 position, 3..5 rotation) of the smooth random motion, in [-1, 1].
  double channel(int c, double t_s) const;

  MotionSpec spec_;
  std::vector<Harmonic> harmonics_;  // 6 channels x kHarmonics
};

}  // namespace tetrapulse::sim
