#pragma once
// Random P3P problems with a known pose, for the solvers' tests and benchmarks.
// Frames and units as in p3p.hpp: the camera at the origin of the OpenCV camera
// frame, target points in metres, p_C = R p_T + t.
#include <random>

#include "tetrapulse/localizer/p3p.hpp"

namespace tetrapulse::testing {

enum class P3PCondition {
  kWell,               // camera 0.5-5 m from a fat triangle, away from every degeneracy
  kNearCollinear,      // X_3 off the line X_1 X_2 by `level` times |X_1 X_2|
  kNearDangerCylinder, // camera centre (1 + level) circumradii from the circumcircle's axis
  kSmallFar,           // a fat triangle of `level` metres side, 3 m away
};

struct P3PProblem {
  Bearing3 x;  // unit bearings of R X_i + t
  Point3x3 X;  // target points
  Pose truth;
};

// `level` is the condition's parameter (ignored for kWell).
P3PProblem random_p3p_problem(std::mt19937_64& rng, P3PCondition condition, double level = 0.0);

// Uniformly distributed rotation.
Eigen::Matrix3d random_rotation(std::mt19937_64& rng);

// Largest of the rotation angle (radians) and the translation error relative to
// |truth.t| between `pose` and `truth`.
double pose_error(const Pose& pose, const Pose& truth);

// Smallest pose_error over the first n candidates (infinity when n = 0).
double best_pose_error(const PoseCandidates& poses, int n, const Pose& truth);

}  // namespace tetrapulse::testing
