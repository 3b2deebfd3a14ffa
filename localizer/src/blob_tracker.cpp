#include "tetrapulse/localizer/blob_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "tetrapulse/localizer/code_clock.hpp"

namespace tetrapulse {

Eigen::Vector2d BlobTrack::predict(int64_t t_ns) const {
  return last_blob_.centroid + velocity_ * (double(t_ns - last_detection_ns_) * 1e-9);
}

int longest_zero_run(const Code& code) {
  if (code.length == 0) return 0;
  int longest = 0, run = 0;
  // Twice round the cycle catches a run that wraps from the end to the start.
  for (uint32_t i = 0; i < 2 * code.length; ++i) {
    run = code.bit(i) ? 0 : run + 1;
    longest = std::max(longest, run);
  }
  return std::min(longest, static_cast<int>(code.length));
}

int longest_dark_frames(const Code& code, int64_t bit_period_ns, int64_t frame_period_ns, int64_t exposure_ns,
                        int cap) {
  if (code.length == 0 || bit_period_ns <= 0 || frame_period_ns <= 0 || exposure_ns <= 0) return 0;
  constexpr int kPhases = 512;
  const Modulation on_off{ModulationKind::kOnOff, 0.0};
  const std::optional<Code> played = code;
  const int64_t period = bit_period_ns * int64_t(code.length);
  int longest = 0;
  for (int k = 0; k < kPhases && longest < cap; ++k) {
    const CodeClock clock{-(period * k) / kPhases, bit_period_ns, 1.0};
    int run = 0;
    while (run < cap && mean_emission(clock, on_off, played, run * frame_period_ns, exposure_ns) < 0.5) ++run;
    longest = std::max(longest, run);
  }
  return std::min(cap, longest + (longest > 0 ? 1 : 0));
}

int coast_frames_for(const TargetsFile& targets, int64_t frame_period_ns, int64_t exposure_ns) {
  if (targets.modulation.kind != ModulationKind::kOnOff) return 1;
  const int64_t T = targets.timebase.bit_period_ns;
  const double frames_per_bit = frame_period_ns > 0 ? double(T) / double(frame_period_ns) : 1.0;
  int frames = 1;
  for (const Target& target : targets.targets)
    for (const Marker& marker : target.markers) {
      if (!marker.code) continue;
      const int run = longest_zero_run(*marker.code);
      if (run == 0) continue;
      if (exposure_ns > 0 && frames_per_bit < 1.0) {
        frames = std::max(frames, longest_dark_frames(*marker.code, T, frame_period_ns, exposure_ns) + 1);
      } else {
        frames = std::max(frames, static_cast<int>(std::ceil(run * frames_per_bit - 1e-9)) + 1);
      }
    }
  return frames;
}

BlobTracker::BlobTracker(BlobTrackerConfig config) : config_(config) {}

const BlobTrack* BlobTracker::find(int64_t id) const {
  const size_t i = index_of(id);
  return i < tracks_.size() ? &tracks_[i] : nullptr;
}

// Tracks are appended with ever larger ids and removed in order: sorted by id,
// so a lookup is a binary search (a linear one, asked for every track of a swarm
// by several stages a frame, grew with the square of the swarm).
size_t BlobTracker::index_of(int64_t id) const {
  const auto it = std::lower_bound(tracks_.begin(), tracks_.end(), id,
                                   [](const BlobTrack& t, int64_t want) { return t.id_ < want; });
  return it != tracks_.end() && it->id_ == id ? size_t(it - tracks_.begin()) : tracks_.size();
}

double BlobTracker::gate_radius(const BlobTrack& track) const {
  return config_.gate_radius_px + config_.gate_growth_px_per_frame * track.missed_;
}

void BlobTracker::add_detection(BlobTrack* track, const ExposureStamp& frame, const Blob& blob) {
  const int64_t t = frame.middle_ns();
  if (track->detections_ > 0 && t > track->last_detection_ns_) {
    track->velocity_ = (blob.centroid - track->last_blob_.centroid) / (double(t - track->last_detection_ns_) * 1e-9);
  }
  track->last_blob_ = blob;
  track->last_detection_ns_ = t;
  ++track->detections_;
  track->missed_ = 0;
  track->updated_ = true;
  TrackSample s;
  s.frame = frame.frame;
  s.timestamp_ns = frame.timestamp_ns;
  s.exposure_ns = frame.exposure_ns;
  s.intensity = blob.intensity;
  s.saturated = blob.saturated;
  s.detected = true;
  s.merged = blob.merged;
  s.merge_group = blob.merge_group;
  s.merge_parts = blob.merge_parts;
  s.streak_half_px = blob.bloomed ? 0.5 * blob.bbox.height : 0;
  s.measured = !blob.merged;  // its light is partly another marker's: no bit from it
  s.centroid = blob.centroid;
  track->history_.push(s);
}

void BlobTracker::add_absence(BlobTrack* track, const ExposureStamp& frame, std::optional<double> intensity,
                              bool saturated) {
  ++track->missed_;
  track->updated_ = true;
  TrackSample s;
  s.frame = frame.frame;
  s.timestamp_ns = frame.timestamp_ns;
  s.exposure_ns = frame.exposure_ns;
  s.intensity = intensity.value_or(0.0);
  s.measured = intensity.has_value();
  s.saturated = saturated;
  s.centroid = track->predict(frame.middle_ns());
  track->history_.push(s);
}

void BlobTracker::update(const ExposureStamp& frame, const BlobExtraction& extraction,
                         const std::vector<TrackGate>& gates) {
  for (BlobTrack& t : tracks_) t.updated_ = false;

  // ROI measurements name their track.
  for (const RoiMeasurement& m : extraction.rois) {
    const size_t i = index_of(m.tag);
    if (i == tracks_.size() || tracks_[i].updated_) continue;
    if (m.status == RoiStatus::kDetected) {
      add_detection(&tracks_[i], frame, m.blob);
    } else if (m.status == RoiStatus::kAbsent) {
      add_absence(&tracks_[i], frame, m.intensity, m.aperture_saturated);
    }
  }

  // The other tracks against the blobs: gated, globally optimal.
  open_tracks_.clear();
  for (size_t i = 0; i < tracks_.size(); ++i)
    if (!tracks_[i].updated_) open_tracks_.push_back(i);
  const int rows = static_cast<int>(open_tracks_.size());
  const int blobs = static_cast<int>(extraction.blobs.size());
  const int cols = blobs + rows;  // one "no blob" column per track
  cost_.assign(size_t(rows) * cols, LinearAssignment::kForbidden);
  const int64_t t = frame.middle_ns();
  for (int r = 0; r < rows; ++r) {
    const BlobTrack& track = tracks_[open_tracks_[size_t(r)]];
    Eigen::Vector2d predicted = track.predict(t);
    double gate = gate_radius(track);
    for (const TrackGate& g : gates)
      if (g.track_id == track.id_ && g.position.allFinite() && std::isfinite(g.radius)) {
        predicted = g.position;
        gate = std::max(g.radius, 0.0);
      }
    for (int c = 0; c < blobs; ++c) {
      if (extraction.blobs[size_t(c)].look != track.last_blob().look) continue;  // a dark ball never continues an LED
      const double d2 = (extraction.blobs[size_t(c)].centroid - predicted).squaredNorm();
      if (d2 <= gate * gate) cost_[size_t(r) * cols + c] = d2;
    }
    cost_[size_t(r) * cols + blobs + r] = gate * gate;
  }
  assignment_.solve(cost_.data(), rows, cols, &assigned_);
  blob_taken_.assign(size_t(blobs), 0);
  blob_track_.assign(size_t(blobs), -1);
  for (int r = 0; r < rows; ++r) {
    const int c = assigned_[size_t(r)];
    if (c >= 0 && c < blobs) {
      add_detection(&tracks_[open_tracks_[size_t(r)]], frame, extraction.blobs[size_t(c)]);
      blob_taken_[size_t(c)] = 1;
      blob_track_[size_t(c)] = tracks_[open_tracks_[size_t(r)]].id_;
    }
  }

  // Coast or delete the tracks that got nothing; then start tracks on the free blobs.
  for (BlobTrack& track : tracks_)
    if (!track.updated_) add_absence(&track, frame, std::nullopt);
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const BlobTrack& track) { return track.missed_ > config_.max_coast_frames; }),
                tracks_.end());
  for (int c = 0; c < blobs; ++c) {
    if (blob_taken_[size_t(c)]) continue;
    BlobTrack track;
    track.id_ = next_id_++;
    blob_track_[size_t(c)] = track.id_;
    add_detection(&track, frame, extraction.blobs[size_t(c)]);
    tracks_.push_back(track);
  }
}

void BlobTracker::predict_rois(const ExposureStamp& frame, double aperture_radius, std::vector<BlobRoi>* rois) const {
  rois->clear();
  for (const BlobTrack& track : tracks_) {
    BlobRoi roi;
    roi.center = track.predict(frame.middle_ns());
    roi.radius = gate_radius(track);
    roi.aperture_radius = aperture_radius;
    roi.tag = track.id_;
    rois->push_back(roi);
  }
}

}  // namespace tetrapulse
