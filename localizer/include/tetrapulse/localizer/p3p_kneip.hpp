#pragma once
#include "tetrapulse/localizer/p3p.hpp"

namespace tetrapulse {

// Camera poses (R, t) with  lambda_i * x_i = R * X_i + t,  lambda_i > 0,  i = 1..3.
// x_i are unit bearing vectors in the camera frame; X_i are target points (metres).
// Kneip, Scaramuzza & Siegwart, "A Novel Parametrization of the Perspective-Three-Point
// Problem for a Direct Computation of Absolute Camera Position and Orientation",
// CVPR 2011: a quartic in cos(theta) solved by Ferrari's method. The breitenmoser
// paper's solver [18]. Returns the number of poses written (0..4).
int p3p_kneip(const Bearing3& x, const Point3x3& X, PoseCandidates* out);

}  // namespace tetrapulse
