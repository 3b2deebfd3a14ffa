#pragma once
// One identified target's pose from the markers seen this frame (Breitenmoser
// et al. 2011, Sec. IV-C), in the camera model's image space:
//   4 markers  refinement (pose_refinement.hpp) from the prediction, or from
//              known-correspondence P4P (p4p.hpp) without one or when the
//              prediction does not converge to a small error;
//   3 markers  P3P gives up to four poses. Where the fourth marker's pixel can
//              be predicted from its own recent track (`hints`), the pose that
//              puts it nearest that pixel is taken when it is clearly the
//              nearest (the others at least three times as far and 4 px
//              further); else the pose closest to the predicted pose, when it
//              is clearly the closest (the others at least twice as far) and
//              near it. Then refined: status kThreeMarkers. Without either
//              prediction three markers give no pose.
// A pose is returned only when its RMS reprojection error is at most
// max_rms_px. With four markers whose pose misses that, each marker is left out
// in turn as above; the one whose absence leaves a pose that fits and agrees
// with the prediction is reported as the outlier.
// Poses as pose.hpp (p_C = R p_T + t, metres); pixels in the OpenCV convention.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/p3p.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

enum class PoseStatus : uint8_t {
  kAllMarkers,    // four markers (or more): the pose needs no prediction
  kThreeMarkers,  // three markers: P3P's poses told apart by the prediction
};
const char* pose_status_name(PoseStatus status);

struct MarkerPoseOptions {
  P3PSolver solver = kDefaultP3PSolver;
  bool sphere_centroid = true;    // the markers' blob centroids as sphere images (sphere_image.hpp)
  double centroid_sigma_px = 0.15;  // centroid noise per axis, for the covariance
  double max_rms_px = 1.5;
  // How near the prediction a three-marker pose must be: rotation (rad) plus
  // translation relative to the distance.
  double max_prediction_distance = 0.35;
};

struct SeenMarker {
  int marker = 0;                                   // 0..3 in the target
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // blob centroid
};

// Where a marker not seen this frame should be, from its track's own motion.
struct HintedMarker {
  int marker = 0;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double uncertainty_px = 2;  // how far the hint may be off
};

struct MarkerPose {
  Pose pose;
  PoseStatus status = PoseStatus::kAllMarkers;
  std::vector<int> used;  // markers the pose used
  int outlier = -1;       // a marker left out because it did not fit, or -1
  double rms_px = 0;
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();  // of (w, v), pose_refinement.hpp
  bool has_covariance = false;
};

// Distance between poses used to compare them with a prediction: rotation angle
// (rad) + |t_a - t_b| / max(|t_b|, 0.1 m).
double pose_distance(const Pose& a, const Pose& b);

std::optional<MarkerPose> solve_marker_pose(const CameraModel& camera, const Target& target,
                                            const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                            const MarkerPoseOptions& options = {},
                                            const std::vector<HintedMarker>& hints = {});

}  // namespace tetrapulse
