#pragma once
// Least-squares pose of one target from its identified markers' blob centroids, in
// the camera model's image space (pixels):
//   minimise over (R, t)   sum_i rho( |h_i(R, t) - u_i|^2 ),   h_i = h(R X_i + t)
// X_i marker centres (target frame, metres), u_i observed centroids (pixels), h the
// camera model's projection of the marker centre or, for markers of known diameter,
// the centroid of the marker sphere's image (sphere_image.hpp); rho the identity or
// a (smooth) Huber loss. Two markers whose spots merged into one blob are one
// observation of their light's centroid, h_i = (1 - s) h(R X_i + t) + s h(R X'_i + t),
// s the partner's share of the light (the centroid of two spots' sum is the
// flux-weighted mean of theirs). Levenberg-Marquardt with the rotation updated on SO(3):
//   R <- exp([w]x) R,  t <- t + v,
// (w, v) in the camera frame: w rotates the target about its origin.
// Breitenmoser et al. 2011, Sec. IV-C, refine the P3P pose with all markers.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <tl/expected.hpp>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/pose.hpp"

namespace tetrapulse {

struct MarkerObservation {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // marker centre, target frame
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();       // observed blob centroid
  // partner_share > 0: the blob is this marker's and the partner's light merged.
  Eigen::Vector3d partner_m = Eigen::Vector3d::Zero();   // the partner's centre, target frame
  double partner_share = 0;                              // s in (0, 1): its share of the light
};

struct RefinementOptions {
  int max_iterations = 50;
  // > 0: Huber loss with this threshold (pixels), in its smooth form
  // rho(s^2) = 2 k^2 (sqrt(1 + s^2/k^2) - 1): quadratic below k, linear above.
  double huber_px = 0;
  // > 0: the centroids' noise per image axis (pixels), used for the covariance.
  // 0: estimated from the residuals when there is redundancy (4 markers or more).
  double sigma_px = 0;
  // > 0: the markers are spheres of this diameter (metres).
  double marker_diameter_m = 0;
  // With a known diameter, predict the centroid of the sphere's image rather than
  // the projection of its centre (through the full lens model, not to first order:
  // the first-order pinhole correction is off by up to 0.36 px on our wide
  // plumb_bob camera; sphere_image_test.cpp).
  bool sphere_centroid = true;
  // False: the pose and its residual only (RefinedPose::has_covariance false), for a
  // caller that compares fits (it saves a third of a tracked pose's refinement).
  bool covariance = true;
};

struct RefinedPose {
  Pose pose;
  double rms_px = 0;          // RMS over markers of |h - u| at the solution
  double initial_rms_px = 0;  // the same at `initial`
  int iterations = 0;        // Levenberg-Marquardt iterations taken
  bool converged = false;    // no further decrease possible (gradient or cost change)
  // Covariance of (w, v) (rad, m) = sigma^2 (J^T W J)^-1 at the solution, W the
  // Huber weights (identity without Huber).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double sigma_px = 0;           // the sigma used (given or estimated)
  // False with three markers and no sigma_px given, where J^T W J is singular, or when
  // RefinementOptions::covariance is off.
  bool has_covariance = false;
};

struct RefinementError {
  enum class Kind { kTooFewMarkers, kNotFinite, kNotInView, kDegenerate };
  Kind kind;
  std::string message;  // names the marker (index in the observations) and what is wrong
};

// Refines `initial` (e.g. from P3P); needs at least three markers, each in front of
// the camera and within its model's field at `initial`.
tl::expected<RefinedPose, RefinementError> refine_pose(const CameraModel& camera,
                                                       const std::vector<MarkerObservation>& markers,
                                                       const Pose& initial, const RefinementOptions& options = {});

}  // namespace tetrapulse
