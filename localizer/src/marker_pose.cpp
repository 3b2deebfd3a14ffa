#include "tetrapulse/localizer/marker_pose.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>

#include "tetrapulse/localizer/p4p.hpp"

namespace tetrapulse {

const char* pose_status_name(PoseStatus status) {
  return status == PoseStatus::kAllMarkers ? "all_markers" : "three_markers";
}

double pose_distance(const Pose& a, const Pose& b) {
  return rotation_angle_between(a.R, b.R) + (a.t - b.t).norm() / std::max(b.t.norm(), 0.1);
}

namespace {

std::optional<MarkerPose> refine(const CameraModel& camera, const Target& target, const std::vector<SeenMarker>& seen,
                                 const Pose& initial, PoseStatus status, const MarkerPoseOptions& options,
                                 const std::vector<MergedMarkers>& merged = {}) {
  std::vector<MarkerObservation> observations;
  for (const SeenMarker& s : seen) observations.push_back({target.markers[size_t(s.marker)].position_m, s.pixel});
  for (const MergedMarkers& m : merged)
    observations.push_back({target.markers[size_t(m.marker)].position_m, m.pixel,
                            target.markers[size_t(m.partner)].position_m, m.partner_share});
  RefinementOptions refinement;
  refinement.marker_diameter_m = target.marker_diameter_m;
  refinement.sphere_centroid = options.sphere_centroid;
  refinement.sigma_px = options.centroid_sigma_px;
  const auto refined = refine_pose(camera, observations, initial, refinement);
  if (!refined) return std::nullopt;
  MarkerPose out;
  out.pose = refined->pose;
  out.status = status;
  for (const SeenMarker& s : seen) out.used.push_back(s.marker);
  for (const MergedMarkers& m : merged) out.used.push_back(m.marker), out.used.push_back(m.partner);
  out.rms_px = refined->rms_px;
  out.covariance = refined->covariance;
  out.has_covariance = refined->has_covariance;
  return out;
}

// The index of the smallest of `score` when it is clearly the smallest: the others
// at least `ratio` times and `gap` larger. -1 otherwise.
int clear_minimum(const std::array<double, 4>& score, int n, double ratio, double gap) {
  int best = -1;
  for (int k = 0; k < n; ++k)
    if (best < 0 || score[size_t(k)] < score[size_t(best)]) best = k;
  if (best < 0 || !std::isfinite(score[size_t(best)])) return -1;
  for (int k = 0; k < n; ++k)
    if (k != best && !(score[size_t(k)] >= ratio * score[size_t(best)] && score[size_t(k)] >= score[size_t(best)] + gap))
      return -1;
  return best;
}

// Three markers: the P3P root that the fourth marker's hint, its light or the
// predicted pose picks out (marker_pose.hpp).
std::optional<MarkerPose> from_three(const CameraModel& camera, const Target& target,
                                     const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                     const MarkerEvidence& evidence, const MarkerPoseOptions& options) {
  Bearing3 x;
  Point3x3 X;
  for (size_t i = 0; i < 3; ++i) {
    if (!camera.unproject(seen[i].pixel, &x[i])) return std::nullopt;
    X[i] = target.markers[size_t(seen[i].marker)].position_m;
  }
  PoseCandidates poses;
  const int n = solve_p3p(options.solver, x, X, &poses);
  int chosen = -1;
  // The hint: the worst of the hinted markers' distances from their hints, in units
  // of their uncertainty.
  const std::vector<HintedMarker>& hints = evidence.hints;
  if (!hints.empty()) {
    std::array<double, 4> off{};
    for (int k = 0; k < n; ++k) {
      double worst = 0;
      for (const HintedMarker& h : hints) {
        Eigen::Vector2d px;
        const double d = camera.project(poses[size_t(k)].apply(target.markers[size_t(h.marker)].position_m), &px)
                             ? (px - h.pixel).norm()
                             : std::numeric_limits<double>::infinity();
        worst = std::max(worst, d / std::max(h.uncertainty_px, 0.5));
      }
      off[size_t(k)] = worst;
    }
    const int best = clear_minimum(off, n, 3.0, 4.0 / std::max(hints.front().uncertainty_px, 0.5));
    if (best >= 0 && off[size_t(best)] <= 3.0) chosen = best;
  }
  const bool by_hint = chosen >= 0;
  std::array<double, 4> d{};
  d.fill(std::numeric_limits<double>::infinity());
  if (prediction)
    for (int k = 0; k < n; ++k) d[size_t(k)] = pose_distance(poses[size_t(k)], *prediction);
  const auto near_prediction = [&](int k) { return d[size_t(k)] <= options.max_prediction_distance; };
  // The light: roots near the prediction whose fourth marker, lit by its code, falls on a blob.
  std::array<int, 4> light_of{-1, -1, -1, -1};  // the blob each root's lit fourth marker falls on
  int explained = 0, explained_root = -1;  // roots whose lit fourth marker falls on a blob
  int lit_marker = -1;
  for (const MissingMarker& m : evidence.missing)
    if (m.light == MarkerLight::kLit) lit_marker = m.marker;
  // Where root k puts the lit fourth marker, and that marker's image diameter (px).
  const auto lit_pixel = [&](int k, Eigen::Vector2d* px, double* diameter_px) {
    const Eigen::Vector3d p = poses[size_t(k)].apply(target.markers[size_t(lit_marker)].position_m);
    *diameter_px = camera.info().fx * target.marker_diameter_m / p.norm();
    return camera.project(p, px);
  };
  if (lit_marker >= 0 && prediction) {
    for (int k = 0; k < n; ++k) {
      if (!near_prediction(k)) continue;
      Eigen::Vector2d px;
      double diameter = 0;
      if (!lit_pixel(k, &px, &diameter)) continue;
      const double reach = std::max(3.0, diameter / 2 + 1.0);
      for (size_t b = 0; b < evidence.lights.size(); ++b)
        if ((evidence.lights[b] - px).norm() <= reach) light_of[size_t(k)] = int(b);
      if (light_of[size_t(k)] >= 0) ++explained, explained_root = k;
    }
  }
  if (chosen < 0 && explained > 0) {
    // The blob is the fourth marker when the four fit one pose: refined from each
    // root that puts it there, the best fit (roots that close converge together).
    std::optional<MarkerPose> best;
    for (int k = 0; k < n; ++k) {
      if (light_of[size_t(k)] < 0) continue;
      std::vector<SeenMarker> four = seen;
      four.push_back(SeenMarker{lit_marker, evidence.lights[size_t(light_of[size_t(k)])]});
      auto out = refine(camera, target, four, poses[size_t(k)], PoseStatus::kAllMarkers, options);
      if (out && out->rms_px <= options.max_rms_px && (!best || out->rms_px < best->rms_px)) best = out;
    }
    if (best) return best;
    if (explained == 1) chosen = explained_root;
  }
  if (chosen < 0 && prediction) {
    const int best = clear_minimum(d, n, 2.0, 0.0);
    // A farther root near the prediction that the fourth marker's light explains: ambiguous.
    if (best >= 0 && near_prediction(best) && !(explained > 0 && light_of[size_t(best)] < 0)) chosen = best;
  }
  if (chosen < 0 || (prediction && !near_prediction(chosen))) return std::nullopt;
  // A lit fourth marker the root puts on one of the three blobs: that blob may hold
  // both (touching balls, a marker behind its neighbour), its centroid neither's.
  if (lit_marker >= 0) {
    Eigen::Vector2d px;
    double diameter = 0;
    if (lit_pixel(chosen, &px, &diameter))
      for (const SeenMarker& s : seen)
        if ((s.pixel - px).norm() <= 1.5 * diameter + 1.0) return std::nullopt;
  }
  auto out = refine(camera, target, seen, poses[size_t(chosen)], PoseStatus::kThreeMarkers, options);
  if (!out || !(out->rms_px <= options.max_rms_px)) return std::nullopt;
  out->hinted = by_hint;
  return out;
}

std::optional<MarkerPose> from_four(const CameraModel& camera, const Target& target,
                                    const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                    const MarkerPoseOptions& options) {
  if (prediction) {
    auto out = refine(camera, target, seen, *prediction, PoseStatus::kAllMarkers, options);
    if (out && out->rms_px <= options.max_rms_px) return out;
  }
  Bearing4 x;
  Point4 X;
  for (size_t i = 0; i < 4; ++i) {
    if (!camera.unproject(seen[i].pixel, &x[i])) return std::nullopt;
    X[i] = target.markers[size_t(seen[i].marker)].position_m;
  }
  P4POptions p4p;
  p4p.solver = options.solver;
  p4p.camera = &camera;
  const auto solution = solve_p4p(x, X, p4p);
  if (!solution) return std::nullopt;
  return refine(camera, target, seen, solution->pose, PoseStatus::kAllMarkers, options);
}

}  // namespace

namespace {

std::optional<MarkerPose> from_seen(const CameraModel& camera, const Target& target,
                                    const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                    const MarkerPoseOptions& options, const MarkerEvidence& evidence);

}  // namespace

std::optional<MarkerPose> solve_marker_pose(const CameraModel& camera, const Target& target,
                                            const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                            const MarkerPoseOptions& options, const MarkerEvidence& evidence) {
  if (evidence.merged.empty()) return from_seen(camera, target, seen, prediction, options, evidence);
  if (seen.size() < 3) {
    if (seen.size() < 2 || !prediction) return std::nullopt;
    auto out = refine(camera, target, seen, *prediction, PoseStatus::kThreeMarkers, options, evidence.merged);
    return out && out->rms_px <= options.max_rms_px ? out : std::nullopt;
  }
  auto pose = from_seen(camera, target, seen, prediction, options, evidence);
  if (!pose) return pose;
  std::vector<SeenMarker> used;
  for (const SeenMarker& s : seen)
    if (std::find(pose->used.begin(), pose->used.end(), s.marker) != pose->used.end()) used.push_back(s);
  auto joined = refine(camera, target, used, pose->pose, pose->status, options, evidence.merged);
  if (joined && joined->rms_px <= options.max_rms_px) {
    joined->outlier = pose->outlier;
    return joined;
  }
  return pose;
}

namespace {

std::optional<MarkerPose> from_seen(const CameraModel& camera, const Target& target,
                                    const std::vector<SeenMarker>& seen, const std::optional<Pose>& prediction,
                                    const MarkerPoseOptions& options, const MarkerEvidence& evidence) {
  if (seen.size() == 3) return from_three(camera, target, seen, prediction, evidence, options);
  if (seen.size() != 4) return std::nullopt;
  auto four = from_four(camera, target, seen, prediction, options);
  if (four) four->four_rms_px = four->rms_px;
  if (four && four->rms_px <= options.max_rms_px) return four;
  if (!prediction) return std::nullopt;
  // One marker does not fit (a blob merged with another light, or a wrong track):
  // the three others, where leaving out one marker agrees best with the prediction.
  std::optional<MarkerPose> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < 4; ++k) {
    std::vector<SeenMarker> three;
    for (size_t i = 0; i < 4; ++i)
      if (i != k) three.push_back(seen[i]);
    auto candidate = from_three(camera, target, three, prediction, MarkerEvidence{}, options);
    if (!candidate) continue;
    const double d = pose_distance(candidate->pose, *prediction);
    if (d < best_d) {
      best_d = d;
      best = candidate;
      best->outlier = seen[k].marker;
      if (four) best->four_rms_px = four->rms_px;
    }
  }
  return best;
}

}  // namespace

}  // namespace tetrapulse
