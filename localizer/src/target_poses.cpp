#include "target_poses.hpp"

#include <algorithm>
#include <vector>

#include "roi_planner.hpp"

namespace tetrapulse::localizer_internal {
namespace {

// The markers seen this frame, and hints for those dark now whose tracks were seen lately.
void markers_of(const TrackedTarget& tt, const BlobTracker& tracker, const ExposureStamp& stamp,
                std::vector<SeenMarker>* seen, std::vector<HintedMarker>* hints) {
  for (int m = 0; m < 4; ++m) {
    const BlobTrack* track = tracker.find(tt.track_of[size_t(m)]);
    if (!track) continue;
    const TrackSample& newest = track->history().newest();
    if (newest.frame == stamp.frame && newest.detected) {
      seen->push_back(SeenMarker{m, newest.centroid});
    } else if (track->detections() >= 2 && track->missed() <= kMaxHintFrames) {
      hints->push_back(HintedMarker{m, track->predict(stamp.middle_ns()), 1.0 + 1.5 * track->missed()});
    }
  }
}

}  // namespace

std::optional<TargetPose> solve_target_pose(const CameraModel& camera, const Target& target, size_t t,
                                            const BlobTracker& tracker, const ExposureStamp& stamp,
                                            int64_t frame_period_ns, const TargetPoseOptions& options,
                                            TargetRoster* roster) {
  TrackedTarget& tt = (*roster)[t];
  const int64_t mid = stamp.middle_ns();
  std::vector<SeenMarker> seen;
  std::vector<HintedMarker> hints;
  markers_of(tt, tracker, stamp, &seen, &hints);
  MarkerPoseOptions pose_options = options.pose;
  if (frame_period_ns > 0) {
    const double since = double(mid - tt.last_pose_ns) / double(frame_period_ns);
    pose_options.max_prediction_distance *= std::max(1.0, 1 + 0.5 * (since - 1));
  }
  const auto solved =
      seen.size() >= 3 ? solve_marker_pose(camera, target, seen, tt.predicted, pose_options, hints) : std::nullopt;
  if (!solved) {
    if (mid - tt.last_pose_ns > options.forget_after_ns) tt.forget();
    return std::nullopt;
  }
  for (int m : solved->used) tt.outlier_frames[size_t(m)] = 0;
  if (solved->outlier >= 0 && ++tt.outlier_frames[size_t(solved->outlier)] >= options.max_outlier_frames)
    tt.release(solved->outlier);
  if (tt.predicted) {
    double sum = 0;
    int n = 0;
    for (const SeenMarker& s : seen) {
      Eigen::Vector2d px;
      if (roster->project_marker(t, s.marker, &px)) sum += (px - s.pixel).norm(), ++n;
    }
    if (n > 0) tt.prediction_error_px = 0.7 * tt.prediction_error_px + 0.3 * (sum / n);
  }
  tt.predictor.add(mid, solved->pose);
  tt.seed.reset();
  tt.last_pose_ns = mid;
  TargetPose p;
  p.target_id = target.id;
  p.mid_exposure_ns = mid;
  p.pose = solved->pose;
  p.status = solved->status;
  p.markers = int(solved->used.size());
  p.rms_px = solved->rms_px;
  p.covariance = solved->covariance;
  p.has_covariance = solved->has_covariance;
  return p;
}

}  // namespace tetrapulse::localizer_internal
