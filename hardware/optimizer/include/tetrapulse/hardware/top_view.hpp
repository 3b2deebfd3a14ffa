#pragma once
// The paper's last optimisation step (Breitenmoser et al. 2011, Sec. III-A): turn each
// target so that it is most distinct seen from the top, i.e. maximise Eq. 1 evaluated
// on the markers' orthogonal projection onto the support plane, with adjusted
// constraints: projected distances in [D1', D2'] and, since projected points have no
// volume, their face height is the smallest altitude of the four projected triangles
// (>= H': no three markers look colinear from above). Only the viewing direction
// matters (a turn about it keeps every projected distance), so each target has two
// parameters: the polar angles of its "up" vector. Lengths in metres.
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

// Adjusted constraints when none are given: D1' = D1 / 2, D2' = D2, H' = H / 2, w' = w.
// The paper does not publish its values; its own target seen along its z axis has
// projected distances 13.3 .. 29.6 cm and triangle altitudes >= 6.3 cm, inside these.
Eq1Limits default_top_view_limits(const Eq1Limits& limits);

// Targets as Eq. 1 sees them from the top, each seen along its own `up` (unit).
std::vector<TargetShape> top_view_shapes(const std::vector<Markers>& targets, const std::vector<Eigen::Vector3d>& up);

struct TopView {
  std::vector<Eigen::Vector3d> up;  // per target, in the frame its markers are given in
  Eq1Score score;                   // Eq. 1 of the projections under the adjusted limits
};

// The best up vectors for the system, jointly (block_ascent over the targets; in every
// sweep each target's simplex starts at the best of its current direction and a fixed
// set of 64 directions, so a target can jump past the others' local optima).
TopView best_top_view(const std::vector<Markers>& targets, const Eq1Limits& top);

// Markers in the target frame: `up` becomes +z (the support plane's normal), the
// projection of marker 1 - marker 0 points along +y, the centroid lies above the
// origin and the lowest marker's centre at z = lift. Markers keep their order.
Markers place_on_support(const Markers& markers, const Eigen::Vector3d& up, double lift);

}  // namespace tetrapulse::hardware
