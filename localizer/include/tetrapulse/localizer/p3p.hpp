#pragma once
// The Perspective-Three-Point problem as our solvers state it:
//   poses (R, t) with  lambda_i * x_i = R * X_i + t,  lambda_i > 0,  i = 1..3,
// x_i unit bearing vectors in the OpenCV camera frame, X_i target points in
// metres (target frame), so that p_C = R * p_T + t. At most four poses exist.
#include <array>

#include <Eigen/Core>

#include "tetrapulse/localizer/pose.hpp"

namespace tetrapulse {

using Bearing3 = std::array<Eigen::Vector3d, 3>;  // unit bearings, camera frame
using Point3x3 = std::array<Eigen::Vector3d, 3>;  // target points, metres
using PoseCandidates = std::array<Pose, 4>;

enum class P3PSolver {
  kLambdaTwist,  // Persson & Nordberg, ECCV 2018 (p3p_lambda_twist.hpp)
  kKneip,        // Kneip, Scaramuzza & Siegwart, CVPR 2011 (p3p_kneip.hpp)
};

// The default. In localizer/tests/p3p_test.cpp it never lost the true pose (to 1e-6)
// near the danger cylinder or on 1-3 cm triangles at 3 m, where Kneip loses 0.005-
// 0.3 %; Kneip does better only for nearly collinear target points, which target
// designs exclude (the paper's H: every face at least 4 marker diameters high).
// Speed: BENCHMARKS.md.
inline constexpr P3PSolver kDefaultP3PSolver = P3PSolver::kLambdaTwist;

const char* p3p_solver_name(P3PSolver solver);

// Calls the chosen solver. Returns the number of poses written (0..4).
int solve_p3p(P3PSolver solver, const Bearing3& x, const Point3x3& X, PoseCandidates* out);

}  // namespace tetrapulse
