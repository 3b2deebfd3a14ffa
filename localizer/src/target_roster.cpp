#include "target_roster.hpp"

#include <algorithm>
#include <vector>

#include "tetrapulse/localizer/target_appearance.hpp"

namespace tetrapulse::localizer_internal {

void TrackedTarget::identify(const std::array<int64_t, 4>& tracks, const CodeClock& code_clock, const Pose& pose,
                             double rms_px, int64_t mid_ns) {
  forget();
  identified = true;
  track_of = tracks;
  for (size_t m = 0; m < 4; ++m) confirmed[m] = tracks[m] >= 0;  // -1: out of view when identified
  clock.start(code_clock, mid_ns);
  seed = pose;
  predicted = pose;
  last_pose_ns = mid_ns;
  identified_ns = mid_ns;
  noise_known = false;
  prediction_error_px = 2;
  prediction_error_rad = 0.1;
  prediction_error_rel = 0.1;
  typical_rms_px = std::clamp(rms_px, 0.0125, 0.5);
  clean_poses = 0;
}

void TrackedTarget::forget() {
  identified = false;
  track_of = {-1, -1, -1, -1};
  outlier_frames = {};
  confirmed = {};
  fits = {};
  vouched_frame = {-1, -1, -1, -1};
  predictor.reset();
  seed.reset();
  clock.forget();
}

TargetRoster::TargetRoster(const CameraModel& camera, const TargetsFile& targets, const PredictionOptions& prediction,
                           double min_roi_radius_px)
    : camera_(camera),
      targets_(targets),
      min_roi_radius_px_(min_roi_radius_px),
      tracked_(targets.targets.size()),
      looks_(rig_looks(BlobExtractorConfig{}, targets).look_of) {
  for (TrackedTarget& t : tracked_) t.predictor = PosePredictor(prediction);
}

void TargetRoster::predict(int64_t mid_ns) {
  for (TrackedTarget& t : tracked_) {
    t.predicted.reset();
    if (!t.identified) continue;
    t.predicted = t.predictor.predict(mid_ns);
    if (!t.predicted && t.seed) t.predicted = t.seed;
  }
}

void TargetRoster::drop_ended_tracks(const BlobTracker& tracker) {
  for (TrackedTarget& t : tracked_)
    for (int m = 0; m < 4; ++m)
      if (t.track_of[size_t(m)] >= 0 && !tracker.find(t.track_of[size_t(m)])) t.release(m);
}

std::optional<MarkerRef> TargetRoster::owner(int64_t track_id) const {
  for (size_t t = 0; t < tracked_.size(); ++t) {
    if (!tracked_[t].identified) continue;
    for (int m = 0; m < 4; ++m)
      if (tracked_[t].track_of[size_t(m)] == track_id) return MarkerRef{t, m};
  }
  return std::nullopt;
}

bool TargetRoster::needs_search() const {
  for (const TrackedTarget& t : tracked_) {
    if (!t.identified) return true;
    for (int64_t id : t.track_of)
      if (id < 0) return true;
  }
  return false;
}

bool TargetRoster::project_marker(size_t t, int m, Eigen::Vector2d* px, double* radius_px) const {
  const TrackedTarget& tt = tracked_[t];
  if (!tt.predicted) return false;
  const Target& target = targets_.targets[t];
  const Eigen::Vector3d p = tt.predicted->apply(target.markers[size_t(m)].position_m);
  if (!camera_.project(p, px)) return false;
  if (radius_px) *radius_px = camera_.info().fx * target.marker_diameter_m / 2 / p.norm();
  return true;
}

std::optional<double> TargetRoster::rig_rms_px(size_t t) const {
  std::vector<double> settled;
  for (size_t i = 0; i < tracked_.size(); ++i)
    if (i != t && tracked_[i].identified && tracked_[i].clean_poses >= kSettledPoses)
      settled.push_back(tracked_[i].typical_rms_px);
  if (settled.empty()) return std::nullopt;
  std::nth_element(settled.begin(), settled.begin() + long(settled.size() / 2), settled.end());
  return settled[settled.size() / 2];
}

double TargetRoster::roi_radius(size_t t, int64_t mid_ns, int64_t frame_period_ns) const {
  const TrackedTarget& tt = tracked_[t];
  const double since = frame_period_ns > 0 ? double(mid_ns - tt.last_pose_ns) / double(frame_period_ns) : 0;
  return std::clamp(2 + 3 * tt.prediction_error_px + 1.5 * std::max(0.0, since - 1), min_roi_radius_px_, 40.0);
}

bool TargetRoster::predicts_closely(size_t t, int64_t mid_ns, int64_t frame_period_ns) const {
  constexpr double kClosePredictionPx = 0.5, kMaxDarkFrames = 4;
  const TrackedTarget& tt = tracked_[t];
  if (frame_period_ns <= 0 || !tt.predicted) return false;
  const double since = double(mid_ns - tt.last_pose_ns) / double(frame_period_ns);
  return since <= kMaxDarkFrames && tt.prediction_error_px <= kClosePredictionPx;
}

}  // namespace tetrapulse::localizer_internal
