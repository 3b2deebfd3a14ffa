#pragma once
// Where the image of a sphere lies, in closed form: the silhouette of a sphere is
// not centred on the projection of the sphere's centre. Sphere of radius r at C
// (camera frame, metres); c = C / |C|; sin(alpha) = r / |C|. Pixels, OpenCV conventions.
//
// Pinhole without distortion: the silhouette is an ellipse in normalized
// coordinates (x, y) = (X/Z, Y/Z) with
//     centre   m = c_z c_xy / (c_z^2 - sin^2 alpha)       (vs c_xy / c_z for the centre's projection)
//     semi-axes a = sin(alpha) cos(alpha) / (c_z^2 - sin^2 alpha)   (along c_xy)
//               b = sin(alpha) / sqrt(c_z^2 - sin^2 alpha)
// and a uniformly bright silhouette has its centroid at m.
//
// Any camera model h (direction -> pixel): in gnomonic coordinates s about c the
// cone is the disc |s| <= rho = tan(alpha), and expanding h to second order,
//     centroid - h(c) = (rho^2 / 4) (Laplacian(h) / 2 + J grad(ln det J)) + O(rho^4),
// with J = dh/ds at s = 0 (derivatives by central differences on the model).
#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/sim/lens_projector.hpp"

namespace tetrapulse::sim {

// Distortion-free pinhole only (the camera's distortion coefficients are ignored).
// False when the cone is not wholly in front of the camera (c_z <= sin alpha).
bool pinhole_silhouette_ellipse(const CameraInfo& camera, const Eigen::Vector3d& centre_C, double radius_m,
                                Eigen::Vector2d* centre_px, double* area_px2);

// Leading-order bias  centroid - project(C)  of the silhouette under any model (pixels).
bool silhouette_centroid_bias(const LensProjector& camera, const Eigen::Vector3d& centre_C, double radius_m,
                              Eigen::Vector2d* bias_px);

}  // namespace tetrapulse::sim
