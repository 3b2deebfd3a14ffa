#include "target_poses.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "disc_occlusion.hpp"
#include "marker_reassociation.hpp"
#include "roi_planner.hpp"
#include "tetrapulse/localizer/code_clock.hpp"

namespace tetrapulse::localizer_internal {
namespace {

constexpr double kMinRmsGatePx = 0.05;  // the fit a pose needs, at the least
// The least typical RMS of a target's four-marker fits (a quarter of the gate).
constexpr double kMinTypicalRmsPx = 0.0125;
constexpr double kMinRotationGate = 0.04;     // rad
constexpr double kMinTranslationGate = 0.03;  // of the distance
// How far from the prediction a pose fitted afresh to the blobs around a target
// (marker_reassociation.hpp) may lie: pose_distance, rad + share of the distance.
constexpr double kMaxReassociationDistance = 0.4;

struct FrameMarkers {
  std::vector<SeenMarker> confirmed, unconfirmed;
  std::vector<std::pair<int, TrackSample>> merged;  // seen markers whose blob was split between predicted markers
  std::vector<int> shared;  // of those, the ones among `unconfirmed`: a confirmed track whose light another shares
  MarkerEvidence evidence;  // hints of confirmed markers dark now, missing markers, lights
};

// Whether a marker not seen is lit now by its code (the fourth blob a pose expects).
bool lit_missing(const MarkerEvidence& evidence) {
  return std::any_of(evidence.missing.begin(), evidence.missing.end(),
                     [](const MissingMarker& m) { return m.light == MarkerLight::kLit; });
}

// What the marker's code says of it in this exposure.
MarkerLight expected_light(const PoseFrame& f, const TrackedTarget& tt, const Marker& marker, int frequency) {
  if (f.targets.modulation.kind == ModulationKind::kConstant || !marker.code) return MarkerLight::kLit;
  if (frequency >= 0) return MarkerLight::kUnknown;
  const ExpectedBit bit = expected_bit(tt.clock.fitted(), *marker.code, f.stamp.timestamp_ns, f.stamp.exposure_ns);
  if (bit == ExpectedBit::kOne) return MarkerLight::kLit;
  if (bit == ExpectedBit::kZero && f.targets.modulation.kind == ModulationKind::kOnOff) return MarkerLight::kDark;
  return MarkerLight::kUnknown;
}

// A marker's light when seen whole: its track's brightest unmerged, unclipped blob
// (grey levels x pixels); 0 when it has none.
double bright_level(const BlobTrack& track) {
  double best = 0;
  for (size_t k = 0; k < track.history().size(); ++k) {
    const TrackSample& s = track.history()[k];
    if (s.detected && s.measured && !s.merged && !s.saturated) best = std::max(best, s.intensity);
  }
  return best;
}

// A blob in which two markers' light merged: the partner's share of the light, and
// how far the farther ball's part in view moves the blob's centroid from where the
// two whole images would put it (pixels: subtracted from the observed centroid).
struct MergedLight {
  double partner_share = 0;
  Eigen::Vector2d far_shift = Eigen::Vector2d::Zero();  // (shift of the far ball's light) x (its share)
};

// Each marker's light seen whole (bright_level) times its code's emission in this
// exposure; of the farther ball only what the nearer one leaves in view at the
// predicted pose (the discs of their images), whose centroid moves away from the
// nearer. The split of the blob between the two predictions gives a share that
// swings from 0.02 to 0.98 between frames as two touching balls overlap (its parts
// follow the predictions, not the light), and a pose of two markers and such a pair
// misses by degrees. Nothing when a level, an emission or the prediction is not known.
std::optional<MergedLight> merged_light(const PoseFrame& f, size_t t, const std::array<int, 4>& frequency_of,
                                        const TargetRoster& roster, int marker, int partner) {
  const TrackedTarget& tt = roster[t];
  const Target& target = f.targets.targets[t];
  double light[2], radius[2];
  Eigen::Vector2d px[2];
  const int markers[2] = {marker, partner};
  for (int k = 0; k < 2; ++k) {
    const int m = markers[k];
    if (frequency_of[size_t(m)] >= 0) return std::nullopt;
    const BlobTrack* track = f.tracker.find(tt.track_of[size_t(m)]);
    const double level = track ? bright_level(*track) : 0;
    if (!(level > 0)) return std::nullopt;
    const Marker& spec = target.markers[size_t(m)];
    light[k] = level * mean_emission(tt.clock.fitted(), f.targets.modulation, spec.code, f.stamp.timestamp_ns,
                                     f.stamp.exposure_ns);
    if (!roster.project_marker(t, m, &px[k], &radius[k])) return std::nullopt;  // no prediction, or behind
  }
  const int far = radius[0] < radius[1] ? 0 : 1, near = 1 - far;  // the smaller image is farther
  const double d = (px[far] - px[near]).norm();
  HiddenPart hidden;  // none for markers of unknown size
  if (radius[far] > 0) {
    hidden = hidden_part(radius[near], radius[far], d);
    light[far] *= 1 - hidden.area / (M_PI * radius[far] * radius[far]);
  }
  if (!(light[0] + light[1] > 0) || !std::isfinite(light[0] + light[1])) return std::nullopt;
  MergedLight out;
  out.partner_share = light[1] / (light[0] + light[1]);
  if (d > 0) out.far_shift = (light[far] / (light[0] + light[1]) * hidden.shift / d) * (px[far] - px[near]);
  if (!out.far_shift.allFinite()) return std::nullopt;
  return out;
}

FrameMarkers markers_of(const PoseFrame& f, size_t t, const std::array<int, 4>& frequency_of,
                        const TargetRoster& roster) {
  const TrackedTarget& tt = roster[t];
  FrameMarkers out;
  std::array<int64_t, 4> seen_track{-1, -1, -1, -1};
  for (int m = 0; m < 4; ++m) {
    const BlobTrack* track = f.tracker.find(tt.track_of[size_t(m)]);
    const bool confirmed = tt.confirmed[size_t(m)];
    if (track) {
      const TrackSample& newest = track->history().newest();
      const bool seen = newest.frame == f.stamp.frame && newest.detected;
      if (seen && cut_by_border(track->last_blob(), f.camera.width(), f.camera.height())) {
        // Its light is partly outside the image: not a measurement of its centre,
        // and no evidence either way of where the pose puts it.
        out.evidence.missing.push_back(MissingMarker{m, MarkerLight::kUnknown});
        seen_track[size_t(m)] = track->id();
        continue;
      }
      if (seen) {
        if (newest.merged && confirmed) {
          out.merged.emplace_back(m, newest);
        } else {
          (confirmed ? out.confirmed : out.unconfirmed).push_back(SeenMarker{m, newest.centroid});
        }
        seen_track[size_t(m)] = track->id();
        continue;
      }
      if (confirmed && track->detections() >= 2 && track->missed() <= kMaxHintFrames)
        out.evidence.hints.push_back(
            HintedMarker{m, track->predict(f.stamp.middle_ns()), 1.0 + 1.5 * track->missed()});
    }
    out.evidence.missing.push_back(
        MissingMarker{m, expected_light(f, tt, f.targets.targets[t].markers[size_t(m)], frequency_of[size_t(m)])});
  }
  // A blob split between two of this target's markers is one observation of their
  // light's centroid; a part of one shared with another target's marker (or split
  // further) leans towards a light that is not this target's.
  std::vector<bool> paired(out.merged.size(), false);
  for (size_t i = 0; i < out.merged.size(); ++i)
    for (size_t j = i + 1; j < out.merged.size(); ++j) {
      const TrackSample& a = out.merged[i].second;
      const TrackSample& b = out.merged[j].second;
      if (a.merge_group != b.merge_group || a.merge_parts != 2 || !(a.intensity + b.intensity > 0)) continue;
      paired[i] = paired[j] = true;
      MergedMarkers pair;
      pair.marker = out.merged[i].first;
      pair.partner = out.merged[j].first;
      pair.partner_share = b.intensity / (a.intensity + b.intensity);
      pair.pixel = (a.intensity * a.centroid + b.intensity * b.centroid) / (a.intensity + b.intensity);
      if (const auto light = merged_light(f, t, frequency_of, roster, pair.marker, pair.partner)) {
        // The model's centroids are the balls' whole images: the observation, less
        // the far ball's shift, is what they would give.
        pair.partner_share = light->partner_share;
        pair.pixel -= light->far_shift;
      }
      out.evidence.merged.push_back(pair);
    }
  // The others may join a pose of four they fit, as an unconfirmed marker would.
  for (size_t i = 0; i < out.merged.size(); ++i)
    if (!paired[i]) {
      out.unconfirmed.push_back(SeenMarker{out.merged[i].first, out.merged[i].second.centroid});
      out.shared.push_back(out.merged[i].first);
    }
  // The frame's other lights are asked only where a missing marker's code lights
  // it (whether a root puts it on a blob): gathered for every target, they cost
  // each pose a pass over every track of the swarm.
  if (!lit_missing(out.evidence)) return out;
  for (const BlobTrack& track : f.tracker.tracks()) {
    const TrackSample& newest = track.history().newest();
    if (newest.frame != f.stamp.frame || !newest.detected) continue;
    if (std::find(seen_track.begin(), seen_track.end(), track.id()) != seen_track.end()) continue;
    out.evidence.lights.push_back(newest.centroid);
  }
  return out;
}

// The pose of all four when an unconfirmed marker is among them and they fit one
// pose; else the pose of the confirmed markers alone (the unconfirmed ones are
// then missing markers whose light is known).
std::optional<MarkerPose> solve(const PoseFrame& f, const Target& target, const TrackedTarget& tt,
                                const MarkerPoseOptions& options, FrameMarkers* markers) {
  const auto from_confirmed = [&]() -> std::optional<MarkerPose> {
    const size_t n = markers->confirmed.size();
    if (n < 3 && !(n == 2 && !markers->evidence.merged.empty())) return std::nullopt;
    return solve_marker_pose(f.camera, target, markers->confirmed, tt.predicted, options, markers->evidence);
  };
  if (markers->unconfirmed.empty()) return from_confirmed();
  std::vector<SeenMarker> all = markers->confirmed;
  all.insert(all.end(), markers->unconfirmed.begin(), markers->unconfirmed.end());
  if (all.size() == 4) {
    auto four = solve_marker_pose(f.camera, target, all, tt.predicted, options, markers->evidence);
    if (four && four->used.size() == 4) return four;
    // Three fit without the fourth, and each of the three is a confirmed track (a
    // part of a split blob is one: only its light is shared): the pose of the
    // three, the prediction's gate still to pass (drones crossing, three of one
    // drone's blobs touching the other's: the parts sit within a few tenths of a
    // pixel, the fourth is pulled).
    const auto known = [&](int m) {
      return std::any_of(markers->confirmed.begin(), markers->confirmed.end(),
                         [m](const SeenMarker& s) { return s.marker == m; }) ||
             std::find(markers->shared.begin(), markers->shared.end(), m) != markers->shared.end();
    };
    if (four && four->used.size() == 3 && four->outlier >= 0 &&
        std::all_of(four->used.begin(), four->used.end(), known) && markers->confirmed.size() < 3)
      return four;
  }
  for (const SeenMarker& s : markers->unconfirmed) {
    markers->evidence.missing.push_back(MissingMarker{s.marker, MarkerLight::kUnknown});
    markers->evidence.lights.push_back(s.pixel);
  }
  return from_confirmed();
}

// The longest code period of a target's markers, ns; 0 for constant markers.
int64_t code_period_ns(const PoseFrame& f, const Target& target) {
  int64_t period = 0;
  for (const Marker& m : target.markers)
    if (m.code) period = std::max(period, int64_t(m.code->length) * f.targets.timebase.bit_period_ns);
  return period;
}

// Whether a pose that rests on the prediction (three markers) agrees with it:
// within max(floor, 4 x the prediction's running error x g), g the square of the
// frames since the last pose (an acceleration's effect on the extrapolation). The
// floor itself does not grow: a target that coasted a few frames on a flat running
// error must not let a flipped root through. A flipped root or a pose through a
// stray marker fails it. (A root the dark marker's own track picked rests on the
// image instead: MarkerPose::hinted.) A ceiling on the growth was tried: it refused
// the true root of a climbing robot turning fast, and the next frame's root nearest
// the stale extrapolation was the wrong one (climb-colour at 900 frames: 42 rows
// up to 88 degrees off).
bool agrees_with_prediction(const TrackedTarget& tt, const Pose& pose, double frames_since) {
  if (!tt.predicted) return false;
  const double growth = std::max(1.0, frames_since * frames_since);
  const double rot = rotation_angle_between(pose.R, tt.predicted->R);
  const double rel = (pose.t - tt.predicted->t).norm() / std::max(tt.predicted->t.norm(), 0.1);
  return rot <= std::max(kMinRotationGate, 4 * tt.prediction_error_rad * growth) &&
         rel <= std::max(kMinTranslationGate, 4 * tt.prediction_error_rel * growth);
}

}  // namespace

std::optional<TargetPose> solve_target_pose(const PoseFrame& f, size_t t, const std::array<int, 4>& frequency_of,
                                            const TargetPoseOptions& options, TargetRoster* roster,
                                            CentroidModel* centroids) {
  TrackedTarget& tt = (*roster)[t];
  const Target& target = f.targets.targets[t];
  const int64_t mid = f.stamp.middle_ns();
  FrameMarkers markers = markers_of(f, t, frequency_of, *roster);
  MarkerPoseOptions pose_options = options.pose;
  pose_options.sphere_centroid = options.pose.sphere_centroid && centroids->sphere();
  pose_options.max_rms_px = std::clamp(4 * tt.typical_rms_px, kMinRmsGatePx, options.pose.max_rms_px);
  // In the frame it is identified its own noise is not known yet, only the fit that
  // identified it: its four markers then fit within 4x the rig's noise, else it
  // waits a frame — no three of them either, as the seed they would be chosen by
  // holds the stray blob too (identified as two drones cross, one blob pulled by
  // the other's marker fitted at 0.53 px and gave a first pose 178 mm off, its best
  // three 214 mm; the next frame fitted at 0.001 px).
  // So for a code period, until four markers have fitted within it: identified
  // beside another drone's touching marker, the identifying fit (0.58 px) was taken
  // for its noise, and lit frames in which that light pulled the marker gave poses
  // 35 mm off for as long as the target was seen.
  const bool noise_unknown = !tt.noise_known && mid - tt.identified_ns <= code_period_ns(f, target);
  const std::optional<double> rig_rms = noise_unknown ? roster->rig_rms_px(t) : std::nullopt;
  if (rig_rms) pose_options.max_rms_px = std::min(pose_options.max_rms_px, std::max(kMinRmsGatePx, 4 * *rig_rms));
  if (f.frame_period_ns > 0) {
    const double frames = double(mid - tt.last_pose_ns) / double(f.frame_period_ns);
    pose_options.max_prediction_distance *= std::max(1.0, 1 + 0.5 * (frames - 1));
  }
  const double since = f.frame_period_ns > 0 ? double(mid - tt.last_pose_ns) / double(f.frame_period_ns) : 1.0;
  // Whether a fourth blob of this target should be in view: a marker on a track not
  // confirmed yet, or one whose code lights it now.
  const bool fourth_expected = !markers.unconfirmed.empty() || lit_missing(markers.evidence);
  auto solved = solve(f, target, tt, pose_options, &markers);
  if (rig_rms && solved && solved->outlier >= 0) solved.reset();
  // A pose of fewer than four confirmed markers rests on the prediction: it must
  // agree with it, unless the dark marker's own track picked its root.
  const bool rests_on_prediction =
      solved && (solved->status == PoseStatus::kThreeMarkers || markers.confirmed.size() < 4);
  if (rests_on_prediction && !solved->hinted && !agrees_with_prediction(tt, solved->pose, since)) solved.reset();
  if (!solved || (solved->used.size() < 4 && fourth_expected)) {
    // Its tracks may have taken each other's blobs: the one assignment of the blobs
    // around it that fits (marker_reassociation.hpp) gives the pose and the tracks.
    // Also when three markers posed it while a fourth was in sight: as two touching
    // balls part, the track of one can follow the other's blob, and the three then
    // fit exactly (P3P) a pose that drifts away frame by frame while the fourth blob
    // is left to an unconfirmed track (climb-colour seed 41: 26 rows to 66 degrees).
    if (auto found = reassociate(f, t, *roster, pose_options, kMaxReassociationDistance)) {
      for (int m = 0; m < 4; ++m) {
        if (tt.track_of[size_t(m)] == found->tracks[size_t(m)]) continue;
        tt.assign(m, found->tracks[size_t(m)]);
        tt.confirmed[size_t(m)] = true;
      }
      solved = found->pose;
      markers = markers_of(f, t, frequency_of, *roster);
    }
  }
  if (!solved) {
    // Holding no track, it has nothing a pose could come from: forgotten now, so that
    // its markers' new tracks identify it again (a code length, not forget_after_ns).
    const bool holds_a_track = std::any_of(tt.track_of.begin(), tt.track_of.end(), [](int64_t id) { return id >= 0; });
    if (!holds_a_track || mid - tt.last_pose_ns > options.forget_after_ns) tt.forget();
    return std::nullopt;
  }
  // A first pose within the rig's noise says more of the target's own than the fit
  // that identified it, which a stray blob may have pulled.
  if (rig_rms && solved->used.size() == 4) {
    tt.typical_rms_px = std::clamp(solved->rms_px, kMinTypicalRmsPx, std::max(tt.typical_rms_px, kMinTypicalRmsPx));
    tt.noise_known = true;
  }
  const bool clean_four = markers.confirmed.size() == 4 && markers.unconfirmed.empty() && markers.evidence.merged.empty();
  if (clean_four && solved->used.size() < 4 && std::isfinite(solved->four_rms_px)) {
    // Four clean markers that missed the gate: one may be pulled, or the rig's
    // noise is more than learned. The typical fit grows towards theirs by at most
    // a fifth a frame: a stray blob lifts it briefly, a noisier rig than the
    // identifying fit showed is learned within a dozen frames.
    tt.typical_rms_px = 0.8 * tt.typical_rms_px + 0.2 * std::min(solved->four_rms_px, 2 * tt.typical_rms_px);
  }
  if (solved->used.size() == 4 && markers.unconfirmed.empty() && markers.evidence.merged.empty()) {
    tt.typical_rms_px = std::max(kMinTypicalRmsPx, 0.8 * tt.typical_rms_px + 0.2 * solved->rms_px);
    ++tt.clean_poses;
    centroids->weigh(f.camera, target, markers.confirmed, solved->pose, solved->rms_px, options.pose.centroid_sigma_px);
  }
  const bool four_fit = solved->used.size() == 4 && markers.evidence.merged.empty();
  for (int m : solved->used) {
    tt.outlier_frames[size_t(m)] = 0;
    if (four_fit) tt.vouched_frame[size_t(m)] = f.stamp.frame;
    const BlobTrack* track = f.tracker.find(tt.track_of[size_t(m)]);
    const bool merged = track && track->history().newest().merged;
    if (!tt.confirmed[size_t(m)] && !merged && solved->used.size() == 4 && ++tt.fits[size_t(m)] >= 2)
      tt.confirmed[size_t(m)] = true;
  }
  if (solved->outlier >= 0 && ++tt.outlier_frames[size_t(solved->outlier)] >= options.max_outlier_frames)
    tt.release(solved->outlier);
  if (tt.predicted) {
    const double rot = rotation_angle_between(solved->pose.R, tt.predicted->R);
    const double rel = (solved->pose.t - tt.predicted->t).norm() / std::max(tt.predicted->t.norm(), 0.1);
    const double per_frame = std::max(1.0, since * since);
    tt.prediction_error_rad = 0.8 * tt.prediction_error_rad + 0.2 * rot / per_frame;
    tt.prediction_error_rel = 0.8 * tt.prediction_error_rel + 0.2 * rel / per_frame;
    double sum = 0;
    int n = 0;
    for (const auto* group : {&markers.confirmed, &markers.unconfirmed})
      for (const SeenMarker& s : *group) {
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
