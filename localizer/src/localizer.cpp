#include "tetrapulse/localizer/localizer.hpp"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "tetrapulse/localizer/code_match.hpp"

namespace tetrapulse {

namespace {

// A tracked target: which track is which marker, and how its pose moves.
struct TargetTrack {
  bool identified = false;
  std::array<int64_t, 4> track_of{-1, -1, -1, -1};
  std::array<int, 4> outlier_frames{};
  PosePredictor predictor;
  std::optional<Pose> predicted;  // at this frame's mid-exposure
  std::optional<Pose> seed;       // the identification's pose, until the first measured one
  int64_t last_pose_ns = 0;
  double prediction_error_px = 2;  // running mean of |observed - predicted| marker pixels
  CodeClock clock;
  // Free-running boards: the clock's origin as re-estimated over time (rate 1),
  // whose drift gives the board's rate.
  int64_t clock_checked_ns = 0;
  std::vector<std::pair<double, double>> origin_drift;  // (s since identification, ns)
  int64_t identified_ns = 0;
  double rate = 1.0;

  void forget() {
    identified = false;
    track_of = {-1, -1, -1, -1};
    outlier_frames = {};
    predictor.reset();
    seed.reset();
    origin_drift.clear();
    rate = 1.0;
  }
};

constexpr int kMaxHintFrames = 2;  // a dark marker's track predicts its pixel this many frames on
constexpr int64_t kSearchTagBase = -2;  // search ROIs: tag = kSearchTagBase - (4 * target + marker)

// Consecutive frames a whole-image search lasts: a marker's longest run of 0 bits
// in frames, + 1. A marker in a 0 bit is dark (on_off) or dim (two_level, easily
// below the locating threshold next to bright lamps): some frame of the burst
// sees every marker lit, whatever its code.
int search_burst_frames(const TargetsFile& targets, int64_t frame_period_ns, int64_t exposure_ns) {
  if (targets.modulation.kind == ModulationKind::kConstant || frame_period_ns <= 0) return 1;
  const int64_t T = targets.timebase.bit_period_ns;
  const double frames_per_bit = double(T) / double(frame_period_ns);
  int frames = 1;
  for (const Target& target : targets.targets)
    for (const Marker& marker : target.markers) {
      if (!marker.code) continue;
      // Bits shorter than a frame (frequency codes): the dark frames come from aliasing.
      const int dark = frames_per_bit < 1.0
                           ? longest_dark_frames(*marker.code, T, frame_period_ns, exposure_ns)
                           : int(std::ceil(longest_zero_run(*marker.code) * frames_per_bit - 1e-9));
      frames = std::max(frames, dark + 1);
    }
  return std::min(frames, 16);
}

}  // namespace

struct Localizer::State {
  State(const CameraInfo& info, const TargetsFile& file, const LocalizerOptions& opts)
      : camera(info),
        targets(file),
        options(opts),
        extractor(opts.blobs),
        identifier(camera, targets, identification_options(opts)),
        rig(rig_codes(targets)),
        frequency_of(frequency_code_of(targets, rig)) {
    for (size_t i = 0; i < targets.targets.size(); ++i) target_tracks.push_back(TargetTrack{});
    for (TargetTrack& t : target_tracks) t.predictor = PosePredictor(options.prediction);
    options.pose.solver = options.p3p;
    coded = targets.modulation.kind != ModulationKind::kConstant;
    free_running = coded && !targets.timebase.synchronized;
    for (const RigCode& c : rig) frequency_coded = frequency_coded || c.frequency;
  }

  static IdentificationOptions identification_options(const LocalizerOptions& o) {
    IdentificationOptions id = o.identification;
    id.solver = o.p3p;
    return id;
  }

  tl::expected<std::vector<TargetPose>, LocalizerError> process(const cv::Mat& image, int64_t start, int64_t exposure);

  // Steps of a frame.
  void predict(int64_t mid);
  void build_rois(int64_t mid);
  tl::expected<void, LocalizerError> extract(const cv::Mat& image);
  void maintain_assignments();
  void read_bits();
  void read_frequencies();
  void verify_codes(int64_t mid);
  void identify(int64_t mid);
  std::vector<TargetPose> solve_poses(int64_t mid);

  // Helpers.
  std::optional<std::pair<size_t, int>> owner(int64_t track_id) const;
  bool project_marker(size_t t, int m, Eigen::Vector2d* px, double* radius_px) const;
  // The prediction's uncertainty: its recent error, growing while no pose comes
  // (extrapolating further, the regression's error grows with the acceleration).
  double roi_radius(const TargetTrack& t) const {
    const double since = frame_period_ns > 0 ? double(stamp.middle_ns() - t.last_pose_ns) / double(frame_period_ns) : 0;
    return std::clamp(2 + 3 * t.prediction_error_px + 1.5 * std::max(0.0, since - 1), options.min_roi_radius_px, 40.0);
  }
  bool needs_search() const;
  void re_estimate_clock(size_t t, int64_t mid);
  // The frequency code a track carries (rig index), -1 while none is decided or it is no frequency code.
  int frequency_code(int64_t track_id);
  bool has_binary_codes(size_t t) const {
    for (int m = 0; m < 4; ++m)
      if (targets.targets[t].markers[size_t(m)].code && frequency_of[t][size_t(m)] < 0) return true;
    return false;
  }
  size_t bits_from(const BlobTrack& track, int samples) const {
    const size_t n = track.history().size();
    return n > size_t(samples) ? n - size_t(samples) : 0;
  }

  CameraModel camera;
  TargetsFile targets;
  LocalizerOptions options;
  bool coded = false;
  bool free_running = false;
  BlobExtractor extractor;
  BlobTracker tracker;
  TargetIdentifier identifier;
  BlobExtraction extraction, whole;
  std::vector<BlobRoi> rois;
  std::vector<TrackGate> gates;
  std::vector<TargetTrack> target_tracks;
  std::unordered_map<int64_t, TrackBitReader> bits;
  std::vector<RigCode> rig;                      // the rig's distinct codes (frequency_identifier.hpp)
  std::vector<std::array<int, 4>> frequency_of;  // each marker's frequency code in `rig` (-1: binary or none)
  bool frequency_coded = false;                  // some marker plays a frequency code
  std::unordered_map<int64_t, FrequencyIdentifier> frequencies;  // per track, while frequency_coded
  struct Pending {
    Eigen::Vector2d centroid;
    size_t target;
    int marker;
  };
  std::vector<Pending> pending;
  ExposureStamp stamp;
  int64_t frames = 0;
  int64_t previous_start = 0;
  int frames_since_search = 0;
  int search_burst_left = 0;
  int64_t frame_period_ns = 0;
  int search_burst = 1;  // search_burst_frames
  bool coast_set = false;
  bool searched = false;
};

std::optional<std::pair<size_t, int>> Localizer::State::owner(int64_t track_id) const {
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    if (!target_tracks[t].identified) continue;
    for (int m = 0; m < 4; ++m)
      if (target_tracks[t].track_of[size_t(m)] == track_id) return std::make_pair(t, m);
  }
  return std::nullopt;
}

bool Localizer::State::project_marker(size_t t, int m, Eigen::Vector2d* px, double* radius_px) const {
  const TargetTrack& tt = target_tracks[t];
  if (!tt.predicted) return false;
  const Target& target = targets.targets[t];
  const Eigen::Vector3d p = tt.predicted->apply(target.markers[size_t(m)].position_m);
  if (!camera.project(p, px)) return false;
  if (radius_px) *radius_px = camera.info().fx * target.marker_diameter_m / 2 / p.norm();
  return true;
}

bool Localizer::State::needs_search() const {
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    const TargetTrack& tt = target_tracks[t];
    if (!tt.identified) return true;
    for (int64_t id : tt.track_of)
      if (id < 0) return true;
  }
  return false;
}

void Localizer::State::predict(int64_t mid) {
  for (TargetTrack& t : target_tracks) {
    t.predicted.reset();
    if (!t.identified) continue;
    t.predicted = t.predictor.predict(mid);
    if (!t.predicted && t.seed) t.predicted = t.seed;
  }
}

void Localizer::State::build_rois(int64_t mid) {
  rois.clear();
  gates.clear();
  const BlobTrackerConfig& tc = tracker.config();
  for (const BlobTrack& track : tracker.tracks()) {
    BlobRoi roi;
    roi.tag = track.id();
    roi.center = track.predict(mid);
    roi.radius = tc.gate_radius_px + tc.gate_growth_px_per_frame * track.missed();
    roi.aperture_radius = std::max(3.0, track.last_blob().radius + 2.5);
    // A tracked target's marker is looked for where its predicted pose puts it, once
    // the pose has a velocity (before that the track's own motion predicts better).
    // A track seen lately also predicts its own pixel; where the two disagree (the
    // target turned since its last pose) the ROI covers both.
    if (const auto o = owner(track.id()); o && target_tracks[o->first].predictor.poses() >= 2) {
      Eigen::Vector2d px;
      if (project_marker(o->first, o->second, &px, nullptr)) {
        double radius = roi_radius(target_tracks[o->first]);
        if (track.missed() <= kMaxHintFrames && track.detections() >= 2) {
          const Eigen::Vector2d own = roi.center;
          radius = std::min(40.0, std::max(radius, 0.5 * (own - px).norm() + options.min_roi_radius_px));
          px = 0.5 * (px + own);
        }
        roi.center = px;
        roi.radius = radius;
        gates.push_back(TrackGate{track.id(), px, roi.radius});
      }
    }
    rois.push_back(roi);
  }
  // Markers of tracked targets that have no track: look where they should be.
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    const TargetTrack& tt = target_tracks[t];
    if (!tt.identified || !tt.predicted) continue;
    for (int m = 0; m < 4; ++m) {
      if (tt.track_of[size_t(m)] >= 0) continue;
      Eigen::Vector2d px;
      double radius = 0;
      if (!project_marker(t, m, &px, &radius) || !camera.in_image(px, -radius)) continue;
      BlobRoi roi;
      roi.tag = kSearchTagBase - int64_t(4 * t + size_t(m));
      roi.center = px;
      roi.radius = roi_radius(tt) + 2;
      roi.aperture_radius = std::max(3.0, radius + 2.5);
      rois.push_back(roi);
    }
  }
}

tl::expected<void, LocalizerError> Localizer::State::extract(const cv::Mat& image) {
  if (auto r = extractor.extract(image, rois, &extraction); !r) return tl::unexpected(LocalizerError{r.error().message});
  // An ROI that found nothing in its square takes the nearest blob its window
  // found outside any square, within twice its radius: a prediction that missed
  // (a sudden turn) still keeps its track.
  for (size_t i = 0; i < extraction.rois.size(); ++i) {
    RoiMeasurement& m = extraction.rois[i];
    if (m.status != RoiStatus::kAbsent) continue;
    const double reach = 2 * rois[i].radius;
    int nearest = -1;
    double nearest_d = reach;
    for (size_t b = 0; b < extraction.blobs.size(); ++b) {
      const double d = (extraction.blobs[b].centroid - rois[i].center).norm();
      if (d < nearest_d) nearest_d = d, nearest = int(b);
    }
    if (nearest < 0) continue;
    // Not when another ROI is nearer to it.
    const Eigen::Vector2d& p = extraction.blobs[size_t(nearest)].centroid;
    bool closer = false;
    for (size_t j = 0; j < rois.size() && !closer; ++j) closer = j != i && (p - rois[j].center).norm() < nearest_d;
    if (closer) continue;
    m.status = RoiStatus::kDetected;
    m.blob = extraction.blobs[size_t(nearest)];
    m.position = m.blob.centroid;
    m.intensity = m.blob.intensity;
    extraction.blobs.erase(extraction.blobs.begin() + nearest);
  }
  // Search ROIs that found a blob start a track, which then joins its marker.
  pending.clear();
  for (const RoiMeasurement& m : extraction.rois) {
    if (m.tag > kSearchTagBase || !m.detected()) continue;
    const int64_t code = kSearchTagBase - m.tag;
    extraction.blobs.push_back(m.blob);
    pending.push_back(Pending{m.blob.centroid, size_t(code / 4), int(code % 4)});
  }
  // While something is not tracked, the whole image is searched in bursts of as
  // many consecutive frames as an on-off marker may stay dark (so that every lit
  // marker shows in one of them, whatever its code), every full_search_interval frames.
  const int burst = std::max(1, search_burst);
  if (frames == 0 || (needs_search() && (search_burst_left > 0 || frames_since_search + 1 >= options.full_search_interval))) {
    if (search_burst_left == 0) search_burst_left = burst;
    --search_burst_left;
    searched = true;
    frames_since_search = 0;
  } else {
    search_burst_left = 0;
    searched = false;
    ++frames_since_search;
    return {};
  }
  const int expected = coded ? 0 : int(4 * targets.targets.size());
  if (auto r = extractor.extract(image, expected, &whole); !r) return tl::unexpected(LocalizerError{r.error().message});
  // Blobs the ROIs own (or already found) are not new.
  const size_t found_in_rois = extraction.blobs.size();
  for (const Blob& b : whole.blobs) {
    bool known = false;
    for (size_t i = 0; i < rois.size() && !known; ++i) {
      const Eigen::Vector2d d = b.centroid - rois[i].center;
      known = std::abs(d.x()) <= rois[i].radius + 1 && std::abs(d.y()) <= rois[i].radius + 1;
    }
    for (size_t i = 0; i < found_in_rois && !known; ++i) known = (b.centroid - extraction.blobs[i].centroid).norm() < 3;
    if (!known) extraction.blobs.push_back(b);
  }
  return {};
}

void Localizer::State::maintain_assignments() {
  for (TargetTrack& t : target_tracks)
    for (int64_t& id : t.track_of)
      if (id >= 0 && !tracker.find(id)) id = -1;
  // Tracks started by a search ROI join the marker they were searched for.
  const auto newborn = [&](const BlobTrack& track) { return track.detections() == 1 && track.history().size() == 1; };
  for (const Pending& p : pending) {
    TargetTrack& tt = target_tracks[p.target];
    if (!tt.identified || tt.track_of[size_t(p.marker)] >= 0) continue;
    for (const BlobTrack& track : tracker.tracks())
      if (newborn(track) && track.last_blob().centroid == p.centroid && !owner(track.id())) {
        tt.track_of[size_t(p.marker)] = track.id();
        tt.outlier_frames[size_t(p.marker)] = 0;
        break;
      }
  }
  // New tracks from the whole image near a missing marker's predicted pixel join it
  // when nothing else is near.
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    TargetTrack& tt = target_tracks[t];
    if (!tt.identified) continue;
    for (int m = 0; m < 4; ++m) {
      Eigen::Vector2d px;
      if (tt.track_of[size_t(m)] >= 0 || !project_marker(t, m, &px, nullptr)) continue;
      const double gate = roi_radius(tt) + 2;
      int64_t found = -1;
      int count = 0;
      for (const BlobTrack& track : tracker.tracks())
        if (newborn(track) && (track.position() - px).norm() <= gate && !owner(track.id())) found = track.id(), ++count;
      if (count == 1) {
        tt.track_of[size_t(m)] = found;
        tt.outlier_frames[size_t(m)] = 0;
      }
    }
  }
}

void Localizer::State::read_bits() {
  // Forget the bits of tracks that ended.
  for (auto it = bits.begin(); it != bits.end();) it = tracker.find(it->first) ? std::next(it) : bits.erase(it);
  if (!coded) return;
  // Identification reads the newest max_samples of unclaimed tracks; code checks
  // the newest verify_samples of claimed ones (all max_samples for a free-running
  // clock's re-estimation). Every track keeps them all current, which costs no
  // more: a reader re-reads only the newest samples, whose bits can still change.
  const int needed = std::max(options.identification.max_samples, options.verify_samples);
  for (const BlobTrack& track : tracker.tracks())
    bits[track.id()].update(track.history(), targets.modulation, options.bits, bits_from(track, needed));
}

void Localizer::State::read_frequencies() {
  if (!frequency_coded) return;
  for (auto it = frequencies.begin(); it != frequencies.end();) it = tracker.find(it->first) ? std::next(it) : frequencies.erase(it);
  for (const BlobTrack& track : tracker.tracks()) {
    const TrackSample& newest = track.history().newest();
    if (newest.frame != stamp.frame) continue;
    frequencies.try_emplace(track.id(), targets, options.frequency).first->second.push(newest);
  }
}

int Localizer::State::frequency_code(int64_t track_id) {
  const auto it = frequencies.find(track_id);
  if (it == frequencies.end()) return -1;
  const FrequencyDecision& d = it->second.decision();
  return d.kind == FrequencyDecision::Kind::kFrequency ? d.code : -1;
}

void Localizer::State::re_estimate_clock(size_t t, int64_t mid) {
  TargetTrack& tt = target_tracks[t];
  const Target& target = targets.targets[t];
  const int64_t T = targets.timebase.bit_period_ns;
  uint32_t length = 1;
  for (const Marker& m : target.markers)
    if (m.code) length = std::max(length, m.code->length);
  if (mid - tt.clock_checked_ns < int64_t(length) * T) return;
  tt.clock_checked_ns = mid;
  // Origins within half a bit of the current one, T / 32 apart, over the samples read_bits keeps current.
  const int needed = std::max(options.identification.max_samples, options.verify_samples);
  constexpr int kSteps = 16;
  std::array<double, 2 * kSteps + 1> cost{};
  for (int k = -kSteps; k <= kSteps; ++k) {
    CodeClock clock = tt.clock;
    clock.rate = 1.0;
    clock.origin_ns = tt.clock.origin_ns + k * T / (2 * kSteps);
    for (int m = 0; m < 4; ++m) {
      const BlobTrack* track = tracker.find(tt.track_of[size_t(m)]);
      if (!track || !target.markers[size_t(m)].code || frequency_of[t][size_t(m)] >= 0) continue;
      cost[size_t(k + kSteps)] +=
          match_code(track->history(), bits[track->id()].bits(), bits_from(*track, needed), clock,
                     *target.markers[size_t(m)].code)
              .cost();
    }
  }
  const double best = *std::min_element(cost.begin(), cost.end());
  int first = -1, last = -1;
  for (int k = 0; k <= 2 * kSteps; ++k)
    if (cost[size_t(k)] == best) {
      if (first < 0) first = k;
      last = k;
    }
  const int k = (first + last) / 2 - kSteps;
  tt.clock.origin_ns += k * T / (2 * kSteps);
  // The board's rate: the drift of the origin (fitted with rate 1), clamped to the contract's 200 ppm.
  const double since = double(mid - tt.identified_ns) * 1e-9;
  tt.origin_drift.emplace_back(since, double(tt.clock.origin_ns - tt.origin_drift.front().second));
  if (tt.origin_drift.size() >= 3 && since >= 2.0) {
    double st = 0, so = 0, stt = 0, sto = 0;
    for (const auto& [s, o] : tt.origin_drift) st += s, so += o, stt += s * s, sto += s * o;
    const double n = double(tt.origin_drift.size());
    const double slope_ns_per_s = (n * sto - st * so) / (n * stt - st * st);
    tt.rate = 1.0 - std::clamp(slope_ns_per_s * 1e-9, -200e-6, 200e-6);
  }
}

void Localizer::State::verify_codes(int64_t mid) {
  if (!coded) return;
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    TargetTrack& tt = target_tracks[t];
    if (!tt.identified) continue;
    if (free_running && has_binary_codes(t)) re_estimate_clock(t, mid);
    for (int m = 0; m < 4; ++m) {
      const Marker& marker = targets.targets[t].markers[size_t(m)];
      const BlobTrack* track = tracker.find(tt.track_of[size_t(m)]);
      if (!track || !marker.code) continue;
      if (const int expected = frequency_of[t][size_t(m)]; expected >= 0) {
        // A frequency track is judged over its whole window, so now and then: one
        // that now carries another code (or a binary one) leaves the marker.
        if ((stamp.frame + track->id()) % std::max(1, options.frequency_check_frames) != 0) continue;
        const auto f = frequencies.find(track->id());
        if (f == frequencies.end()) continue;
        const FrequencyDecision& d = f->second.decision();
        if (d.decided() && (d.kind != FrequencyDecision::Kind::kFrequency || d.code != expected)) tt.track_of[size_t(m)] = -1;
        continue;
      }
      const CodeClock clock{tt.clock.origin_ns, tt.clock.bit_period_ns, 1.0};
      const CodeMatch check = match_code(track->history(), bits[track->id()].bits(),
                                         bits_from(*track, options.verify_samples), clock, *marker.code);
      if (check.mismatches > options.verify_max_errors) tt.track_of[size_t(m)] = -1;
    }
  }
}

void Localizer::State::identify(int64_t mid) {
  std::vector<bool> wanted(target_tracks.size());
  bool any = false;
  for (size_t t = 0; t < target_tracks.size(); ++t) any |= (wanted[t] = !target_tracks[t].identified);
  if (!any) return;
  std::vector<CandidateTrack> candidates;
  static const TrackBits kNoBits = [] {
    TrackBits b;
    b.fill(ReadBit::kUnknown);
    return b;
  }();
  for (const BlobTrack& track : tracker.tracks()) {
    if (owner(track.id())) continue;
    CandidateTrack c;
    c.track = &track;
    const auto it = bits.find(track.id());
    c.bits = it != bits.end() ? &it->second.bits() : &kNoBits;
    const TrackSample& newest = track.history().newest();
    c.pixel = newest.frame == stamp.frame && newest.detected ? newest.centroid : track.predict(mid);
    c.radius_px = track.last_blob().radius;
    if (frequency_coded) c.frequency_code = frequency_code(track.id());
    candidates.push_back(c);
  }
  if (candidates.size() < 4) return;
  for (const Identification& id : identifier.identify(candidates, wanted)) {
    TargetTrack& tt = target_tracks[id.target];
    tt.forget();
    tt.identified = true;
    tt.track_of = id.track_of;
    tt.clock = id.clock;
    tt.seed = id.pose;
    tt.predicted = id.pose;
    tt.last_pose_ns = mid;
    tt.identified_ns = mid;
    tt.clock_checked_ns = mid;
    tt.origin_drift.emplace_back(0.0, double(id.clock.origin_ns));
    tt.prediction_error_px = 2;
  }
}

std::vector<TargetPose> Localizer::State::solve_poses(int64_t mid) {
  std::vector<TargetPose> out;
  for (size_t t = 0; t < target_tracks.size(); ++t) {
    TargetTrack& tt = target_tracks[t];
    if (!tt.identified) continue;
    const Target& target = targets.targets[t];
    std::vector<SeenMarker> seen;
    std::vector<HintedMarker> hints;
    for (int m = 0; m < 4; ++m) {
      const BlobTrack* track = tracker.find(tt.track_of[size_t(m)]);
      if (!track) continue;
      const TrackSample& newest = track->history().newest();
      if (newest.frame == stamp.frame && newest.detected) {
        seen.push_back(SeenMarker{m, newest.centroid});
      } else if (track->detections() >= 2 && track->missed() <= kMaxHintFrames) {
        // Dark this frame (a 0 bit): its track's own motion says where it is.
        hints.push_back(HintedMarker{m, track->predict(mid), 1.0 + 1.5 * track->missed()});
      }
    }
    // The prediction is trusted less the further it extrapolates.
    MarkerPoseOptions pose_options = options.pose;
    if (frame_period_ns > 0) {
      const double since = double(mid - tt.last_pose_ns) / double(frame_period_ns);
      pose_options.max_prediction_distance *= std::max(1.0, 1 + 0.5 * (since - 1));
    }
    const auto solved = seen.size() >= 3 ? solve_marker_pose(camera, target, seen, tt.predicted, pose_options, hints)
                                         : std::nullopt;
    if (!solved) {
      if (mid - tt.last_pose_ns > options.forget_after_ns) tt.forget();
      continue;
    }
    for (int m : solved->used) tt.outlier_frames[size_t(m)] = 0;
    if (solved->outlier >= 0 && ++tt.outlier_frames[size_t(solved->outlier)] >= options.max_outlier_frames) {
      tt.track_of[size_t(solved->outlier)] = -1;
      tt.outlier_frames[size_t(solved->outlier)] = 0;
    }
    if (tt.predicted) {
      double sum = 0;
      int n = 0;
      for (const SeenMarker& s : seen) {
        Eigen::Vector2d px;
        if (project_marker(t, s.marker, &px, nullptr)) sum += (px - s.pixel).norm(), ++n;
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
    out.push_back(p);
  }
  return out;
}

tl::expected<std::vector<TargetPose>, LocalizerError> Localizer::State::process(const cv::Mat& image, int64_t start,
                                                                                int64_t exposure) {
  if (image.cols != camera.width() || image.rows != camera.height()) {
    return tl::unexpected(LocalizerError{
        fmt::format("image is {}x{}, the camera {}x{}", image.cols, image.rows, camera.width(), camera.height())});
  }
  if (exposure <= 0) return tl::unexpected(LocalizerError{fmt::format("exposure of {} ns is not positive", exposure)});
  if (frames > 0 && start <= previous_start) {
    return tl::unexpected(LocalizerError{
        fmt::format("exposure starts at {} ns, not after the previous frame's {} ns", start, previous_start)});
  }
  if (frames > 0 && !coast_set) {
    // On-off codes darken a marker for a run of 0 bits: its track must outlive it.
    frame_period_ns = start - previous_start;
    tracker.set_max_coast_frames(
        std::max(tracker.config().max_coast_frames, coast_frames_for(targets, frame_period_ns, exposure)));
    search_burst = search_burst_frames(targets, frame_period_ns, exposure);
    search_burst_left = search_burst - 1;  // the first burst began with frame 0
    coast_set = true;
  }
  stamp = ExposureStamp{frames, start, exposure};
  const int64_t mid = stamp.middle_ns();
  predict(mid);
  build_rois(mid);
  if (auto r = extract(image); !r) return tl::unexpected(r.error());
  tracker.update(stamp, extraction, gates);
  maintain_assignments();
  read_bits();
  read_frequencies();
  verify_codes(mid);
  identify(mid);
  auto poses = solve_poses(mid);
  previous_start = start;
  ++frames;
  return poses;
}

Localizer::Localizer(const CameraInfo& camera, const TargetsFile& targets, LocalizerOptions options)
    : state_(std::make_unique<State>(camera, targets, options)) {}
Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

tl::expected<std::vector<TargetPose>, LocalizerError> Localizer::process(const cv::Mat& image,
                                                                         int64_t exposure_start_ns,
                                                                         int64_t exposure_ns) {
  return state_->process(image, exposure_start_ns, exposure_ns);
}

const CameraModel& Localizer::camera() const { return state_->camera; }
const TargetsFile& Localizer::targets() const { return state_->targets; }
const BlobExtraction& Localizer::extraction() const { return state_->extraction; }
const BlobTracker& Localizer::tracker() const { return state_->tracker; }
bool Localizer::searched_whole_image() const { return state_->searched; }

std::vector<TrackLabel> Localizer::track_labels() const {
  std::vector<TrackLabel> out;
  for (const BlobTrack& track : state_->tracker.tracks()) {
    TrackLabel label;
    label.track_id = track.id();
    if (const auto o = state_->owner(track.id())) {
      label.target_id = state_->targets.targets[o->first].id;
      label.marker = o->second;
    }
    out.push_back(label);
  }
  return out;
}

std::optional<CodeClock> Localizer::clock_of(int target_id) const {
  for (size_t t = 0; t < state_->target_tracks.size(); ++t) {
    const TargetTrack& tt = state_->target_tracks[t];
    if (state_->targets.targets[t].id != target_id || !tt.identified) continue;
    // The origin was fitted with rate 1 at the last check; with the estimated rate
    // the same bit starts there: (tau - o) = (tau - o') rate.
    CodeClock c = tt.clock;
    c.rate = tt.rate;
    const double tau = double(tt.clock_checked_ns);
    c.origin_ns = int64_t(std::llround(tau - (tau - double(tt.clock.origin_ns)) / tt.rate));
    return c;
  }
  return std::nullopt;
}

}  // namespace tetrapulse
