#pragma once
// Internal to Localizer: what it knows of each target of the targets file from
// frame to frame — whether it is identified, which blob track is which of its
// markers, how its pose moves and where it is predicted this frame, and its
// board's clock. Poses as pose.hpp; pixels OpenCV; times in rig-time ns.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "target_clock.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/pose_predictor.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse::localizer_internal {

// A marker of a target: index into TargetsFile::targets, and 0..3.
struct MarkerRef {
  size_t target = 0;
  int marker = 0;
};

struct TrackedTarget {
  bool identified = false;
  std::array<int64_t, 4> track_of{-1, -1, -1, -1};  // blob track of each marker, -1: none
  std::array<int, 4> outlier_frames{};              // frames in a row each was left out of the pose
  // A marker's track is confirmed once it is known to be that marker: from the
  // identification, or (a track that joined later) once its code has matched over
  // a whole code length or it has fitted two four-marker poses. Until then it
  // never decides a pose alone (no three-marker pose, no root choice).
  std::array<bool, 4> confirmed{};
  std::array<int, 4> fits{};  // four-marker poses an unconfirmed track fitted
  // The last frame each marker's track was one of four markers that fitted one
  // pose (-1: none since it took the track). Geometry then vouched for it: a
  // track followed without a merge since keeps that identity, so read errors
  // alone (both levels clipped, codes unreadable) do not take it away.
  std::array<int64_t, 4> vouched_frame{-1, -1, -1, -1};
  PosePredictor predictor;
  std::optional<Pose> predicted;  // at this frame's mid-exposure
  std::optional<Pose> seed;       // the identification's pose, until the first measured one
  int64_t last_pose_ns = 0;
  int64_t identified_ns = 0;
  double prediction_error_px = 2;  // running mean of |observed - predicted| marker pixels
  // Running means of how far measured poses lay from their predictions: rotation
  // angle (rad) and translation relative to the distance. They size the gate a
  // pose that rests on the prediction (three markers) must pass.
  double prediction_error_rad = 0.1;
  double prediction_error_rel = 0.1;
  // Running mean of the RMS reprojection error of its poses of four confirmed,
  // unmerged markers: the level of its centroids' noise. A pose that fits four
  // times worse holds a marker that is not where it seems (a blob merged with
  // another light, a stray track).
  double typical_rms_px = 0.5;
  int clean_poses = 0;  // poses of four confirmed, unmerged markers since identified
  // Whether typical_rms_px comes from a four-marker pose within the rig's noise
  // rather than from the identifying fit (which a stray blob may have pulled).
  bool noise_known = false;
  TargetClock clock;

  // Identified by `clock` and `pose` (fitting its four markers with RMS `rms_px`)
  // at `mid_ns`, its markers on `tracks`.
  void identify(const std::array<int64_t, 4>& tracks, const CodeClock& code_clock, const Pose& pose, double rms_px,
                int64_t mid_ns);
  void forget();
  void release(int marker) { assign(marker, -1); }
  void assign(int marker, int64_t track_id) {
    track_of[size_t(marker)] = track_id;
    outlier_frames[size_t(marker)] = 0;
    confirmed[size_t(marker)] = false;
    fits[size_t(marker)] = 0;
    vouched_frame[size_t(marker)] = -1;
  }
};

class TargetRoster {
 public:
  TargetRoster(const CameraModel& camera, const TargetsFile& targets, const PredictionOptions& prediction,
               double min_roi_radius_px);

  size_t size() const { return tracked_.size(); }
  TrackedTarget& operator[](size_t t) { return tracked_[t]; }
  const TrackedTarget& operator[](size_t t) const { return tracked_[t]; }

  // Each identified target's pose at `mid_ns` (the seed until a pose is measured).
  void predict(int64_t mid_ns);
  // Markers lose the tracks that ended.
  void drop_ended_tracks(const BlobTracker& tracker);

  // The identified target and marker that `track_id` is, if any.
  std::optional<MarkerRef> owner(int64_t track_id) const;
  // Some target is not identified, or some marker of an identified one has no track.
  bool needs_search() const;
  // The look of marker `m` of target `t` (Blob::look, RigLooks::look_of).
  int look_of(size_t t, int m) const { return looks_[t][size_t(m)]; }

  // Where the predicted pose puts marker `m` of target `t` (false without a
  // prediction, or behind the camera); its image radius when `radius_px` is given.
  bool project_marker(size_t t, int m, Eigen::Vector2d* px, double* radius_px = nullptr) const;
  // Half side of the square a target's markers are searched in: the prediction's
  // recent error, growing while no pose comes (extrapolating further, the
  // regression's error grows with the acceleration). frame_period_ns 0: unknown yet.
  double roi_radius(size_t t, int64_t mid_ns, int64_t frame_period_ns) const;
  // Whether target t was posed within the last few frames (a dark run) and its
  // predictions have been hitting its markers within half a pixel: its markers'
  // image radii are then known, and a much larger blob beside one is another light.
  bool predicts_closely(size_t t, int64_t mid_ns, int64_t frame_period_ns) const;
  // The rig's centroid noise: the median typical_rms_px of the identified targets
  // with at least kSettledPoses clean poses, other than `t`; none without one.
  std::optional<double> rig_rms_px(size_t t) const;
  static constexpr int kSettledPoses = 3;

 private:
  const CameraModel& camera_;
  const TargetsFile& targets_;
  double min_roi_radius_px_;
  std::vector<TrackedTarget> tracked_;  // one per TargetsFile::targets entry
  std::vector<std::array<int, 4>> looks_;
};

}  // namespace tetrapulse::localizer_internal
