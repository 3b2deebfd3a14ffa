#include "roi_planner.hpp"

#include <algorithm>

namespace tetrapulse::localizer_internal {

double aperture_radius_for(const BlobTrack& track) {
  constexpr double kMarginPx = 2.5, kMaxPx = 64;
  constexpr size_t kRecent = 16;
  const Blob& last = track.last_blob();
  double extent = last.radius;
  const auto& history = track.history();
  for (size_t i = history.size() > kRecent ? history.size() - kRecent : 0; i < history.size(); ++i)
    extent = std::max(extent, history[i].streak_half_px);
  if (last.bloomed && last.clipped) extent = std::max(extent, 1.5 * 0.5 * last.bbox.height);
  return std::clamp(extent + kMarginPx, 3.0, kMaxPx);
}

void plan_rois(const TargetRoster& roster, const BlobTracker& tracker, const CameraModel& camera, int64_t mid_ns,
               int64_t frame_period_ns, double min_roi_radius_px, RoiPlan* plan) {
  plan->rois.clear();
  plan->purposes.clear();
  plan->gates.clear();
  const BlobTrackerConfig& tc = tracker.config();
  for (const BlobTrack& track : tracker.tracks()) {
    BlobRoi roi;
    roi.tag = track.id();
    roi.center = track.predict(mid_ns);
    roi.radius = tc.gate_radius_px + tc.gate_growth_px_per_frame * track.missed();
    roi.aperture_radius = aperture_radius_for(track);
    bool exact = false;
    double marker_radius = 0;
    if (const auto o = roster.owner(track.id()); o && roster[o->target].predictor.poses() >= 2) {
      Eigen::Vector2d px;
      if (roster.project_marker(o->target, o->marker, &px, &marker_radius)) {
        double radius = roster.roi_radius(o->target, mid_ns, frame_period_ns);
        exact = roster.predicts_closely(o->target, mid_ns, frame_period_ns);
        if (track.missed() <= kMaxHintFrames && track.detections() >= 2) {
          const Eigen::Vector2d own = roi.center;
          radius = std::min(40.0, std::max(radius, 0.5 * (own - px).norm() + min_roi_radius_px));
          px = 0.5 * (px + own);
        }
        roi.center = px;
        roi.radius = radius;
        roi.splits = true;
        plan->gates.push_back(TrackGate{track.id(), px, roi.radius});
      }
    }
    plan->rois.push_back(roi);
    plan->purposes.push_back(RoiPurpose{track.id(), std::nullopt, track.last_blob().look, exact, marker_radius});
  }
  for (size_t t = 0; t < roster.size(); ++t) {
    const TrackedTarget& tt = roster[t];
    if (!tt.identified || !tt.predicted) continue;
    for (int m = 0; m < 4; ++m) {
      if (tt.track_of[size_t(m)] >= 0) continue;
      Eigen::Vector2d px;
      double radius = 0;
      if (!roster.project_marker(t, m, &px, &radius) || !camera.in_image(px, -radius)) continue;
      BlobRoi roi;
      roi.tag = -1;
      roi.splits = true;
      roi.center = px;
      roi.radius = roster.roi_radius(t, mid_ns, frame_period_ns) + 2;
      roi.aperture_radius = std::max(3.0, radius + 2.5);
      plan->rois.push_back(roi);
      plan->purposes.push_back(RoiPurpose{-1, MarkerRef{t, m}, roster.look_of(t, m)});
    }
  }
}

}  // namespace tetrapulse::localizer_internal
