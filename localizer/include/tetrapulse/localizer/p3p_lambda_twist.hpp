#pragma once
#include "tetrapulse/localizer/p3p.hpp"

namespace tetrapulse {

// Camera poses (R, t) with  lambda_i * x_i = R * X_i + t,  lambda_i > 0,  i = 1..3.
// x_i are unit bearing vectors in the camera frame; X_i are target points (metres).
// Persson & Nordberg, "Lambda Twist: An Accurate Fast Robust Perspective Three Point
// (P3P) Solver", ECCV 2018: the three distance equations
//   Lambda^T M_ij Lambda = |X_i - X_j|^2
// pairwise combined into two homogeneous conics D1, D2; a root gamma of the cubic
// det(D1 + gamma D2) = 0 makes D0 = D1 + gamma D2 a pair of lines (split here with
// D0's adjugate rather than the paper's eigen decomposition); each line meets the
// conics in up to two Lambda, refined by Gauss-Newton on the distance equations.
// Returns the number of poses written (0..4).
int p3p_lambda_twist(const Bearing3& x, const Point3x3& X, PoseCandidates* out);

}  // namespace tetrapulse
