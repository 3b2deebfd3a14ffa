#pragma once
// One identified target's pose from the markers seen this frame (Breitenmoser
// et al. 2011, Sec. IV-C), in the camera model's image space:
//   4 markers  refinement (pose_refinement.hpp) from the prediction, or from
//              known-correspondence P4P (p4p.hpp) without one or when the
//              prediction does not converge to a small error;
//   3 markers  P3P gives up to four poses (roots), of which the paper keeps
//              the one the fourth marker's reprojection fits, else the one
//              closest to the prediction. In that order:
//              - a hint: where the fourth marker's pixel is predicted from its
//                own recent track (`hints`), the root that puts it nearest is
//                taken when it is clearly the nearest (the others at least
//                three times as far and 4 px further);
//              - its light: when the fourth marker's code says it is lit in this
//                exposure (MissingMarker), the roots near the prediction whose
//                fourth-marker pixel holds a blob of this frame (`lights`)
//                explain the image; exactly one such root is taken, refined
//                with that blob as a fourth marker when it fits;
//              - the prediction: the root closest to the predicted pose when it
//                is clearly the closest (the others at least twice as far),
//                unless a farther root near the prediction is the one the
//                fourth marker's light explains (then the ambiguity stands);
//              every root taken must lie within max_prediction_distance of the
//              prediction, and must not put a lit fourth marker on one of the
//              three blobs (within 1.5 of its image diameters + 1 px: that blob
//              may hold both, its centroid neither's). Then refined: status kThreeMarkers (`hinted` when
//              the hint picked the root). Without a prediction only a hint picks
//              a root; an unresolved ambiguity gives no pose.
// A pose is returned only when its RMS reprojection error is at most
// max_rms_px. With four markers whose pose misses that, each marker is left out
// in turn as above; the one whose absence leaves a pose that fits and agrees
// with the prediction is reported as the outlier.
// Poses as pose.hpp (p_C = R p_T + t, metres); pixels in the OpenCV convention.
#include <limits>
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

// What a marker not seen this frame should look like, from its code and clock.
enum class MarkerLight : uint8_t {
  kUnknown,  // mixed exposure, frequency code, or no clock
  kLit,      // its code plays a 1 (or it is unmodulated): a blob should be there, unless hidden
  kDark,     // its code plays a 0 (on_off): nothing should be there
};

struct MissingMarker {
  int marker = 0;
  MarkerLight light = MarkerLight::kUnknown;
};

// Two markers whose spots merged into one blob: the centroid of their light
// (pose_refinement.hpp), with the partner's share of it.
struct MergedMarkers {
  int marker = 0;
  int partner = 0;
  double partner_share = 0.5;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

// What else the frame shows, for telling P3P's roots apart.
struct MarkerEvidence {
  std::vector<HintedMarker> hints;     // markers dark now whose tracks predict their pixels
  std::vector<MissingMarker> missing;  // markers not seen, with what their codes say
  // Centroids of this frame's blobs that are none of the seen markers: read only
  // when a missing marker is kLit (a caller may leave it empty otherwise).
  std::vector<Eigen::Vector2d> lights;
  // Pairs of markers merged into one blob: they join the refinement of a pose the
  // seen markers give; with two seen markers, they make a pose refined from the
  // prediction (status kThreeMarkers).
  std::vector<MergedMarkers> merged;
};

struct MarkerPose {
  Pose pose;
  PoseStatus status = PoseStatus::kAllMarkers;
  std::vector<int> used;  // markers the pose used
  int outlier = -1;       // a marker left out because it did not fit, or -1
  // Three markers: the root was the one the fourth marker's own track (its hint)
  // picked, evidence of the image rather than of the prediction.
  bool hinted = false;
  double rms_px = 0;
  // Four markers seen: the RMS of their best four-marker fit, also when it missed
  // max_rms_px and three of them gave the pose (NaN when four were not fitted).
  double four_rms_px = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();  // of (w, v), pose_refinement.hpp
  bool has_covariance = false;
};

// Distance between poses used to compare them with a prediction: rotation angle
// (rad) + |t_a - t_b| / max(|t_b|, 0.1 m).
double pose_distance(const Pose& a, const Pose& b);

std::optional<MarkerPose> solve_marker_pose(const CameraModel& camera, const Target& target,
                                            const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                            const MarkerPoseOptions& options = {},
                                            const MarkerEvidence& evidence = {});

}  // namespace tetrapulse
