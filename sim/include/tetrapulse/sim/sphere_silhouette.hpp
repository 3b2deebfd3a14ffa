#pragma once
// The image of a glowing sphere, drawn physically: the sphere of radius r centred
// at C (camera frame, metres) fills the cone of directions within alpha of
// c = C / |C|, sin(alpha) = r / |C|. Its silhouette's outline is the image of
// the cone's boundary,
//     d(phi) = cos(alpha) c + sin(alpha) (cos(phi) e1 + sin(phi) e2),   phi in [0, 2 pi),
// mapped through the camera model (pixels, OpenCV conventions: integer
// coordinates are pixel centres). The outline is a polygon through points of
// that curve, dense enough that no chord strays more than `tolerance_px` from it,
// its vertices pushed out by the chords' mean gap so that it keeps the silhouette's area.
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/sim/lens_projector.hpp"

namespace tetrapulse::sim {

// Writes the outline (pixels) of the sphere's silhouette. Returns false when the
// camera is inside the sphere or some direction of the cone cannot be projected
// (behind the camera or outside the model's range): such a sphere is not drawn.
bool sphere_outline(const LensProjector& camera, const Eigen::Vector3d& centre_C, double radius_m, double tolerance_px,
                    std::vector<Eigen::Vector2d>* outline);

// Cone half-angle alpha of the sphere seen from the camera (radians); NaN when the camera is inside.
double sphere_half_angle(const Eigen::Vector3d& centre_C, double radius_m);

}  // namespace tetrapulse::sim
