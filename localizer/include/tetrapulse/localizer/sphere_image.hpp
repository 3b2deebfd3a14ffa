#pragma once
// Where a spherical marker's blob centroid lies. A sphere of radius r centred at C
// (camera frame, metres) is seen as the cone of rays at half-angle alpha around
// c = C/|C|, sin(alpha) = r/|C|. Its image is not centred on the projection of C:
// through a pinhole, in normalized coordinates, the image is an ellipse centred at
//   c_z c_xy / (c_z^2 - sin^2 alpha)   instead of   c_xy / c_z,
// and a lens's distortion bends it further by terms of the same order (alpha^2).
// About 0.1-0.3 px near the corners of a 90 degree camera for a 3 cm sphere at 1 m.
#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"

namespace tetrapulse {

// Pixel of the area centroid of the sphere's image (a thresholded blob's centroid,
// as the paper computes it): the silhouette cone's rim is projected through the full
// camera model, distortion included, and the region it bounds integrated with
// Green's theorem at `rim_points` points of the rim (8 points: within 2e-6 px of
// the converged value for a 3 cm sphere at 1 m anywhere on our test cameras).
// False when the rim does not project (part of the sphere outside the model's
// field, or the camera inside the sphere).
bool sphere_image_centroid(const CameraModel& camera, const Eigen::Vector3d& centre, double radius,
                           Eigen::Vector2d* px, int rim_points = 8);

}  // namespace tetrapulse
