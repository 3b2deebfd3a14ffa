#pragma once
// Blob tracks: each marker's blobs followed from frame to frame, with the
// intensity history that temporal decoding reads.
//
// Per frame, tracks are matched to blobs by a globally optimal assignment
// (LinearAssignment) minimising the sum of squared distances between each
// track's predicted position and its blob, within the track's gate; leaving a
// track unmatched costs its gate radius squared. The prediction is the
// caller's (TrackGate: e.g. a marker projected from a predicted pose) when
// given, else the track's own constant-velocity image motion. A track with no
// blob coasts on its prediction for up to max_coast_frames frames (an on_off
// marker is dark during a run of 0 bits), then is deleted. Unmatched blobs
// start new tracks; track ids are never reused.
//
// Positions in pixels (OpenCV convention, as Blob); times in integer
// nanoseconds of rig time; velocities in pixels per second.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/blob.hpp"
#include "tetrapulse/localizer/linear_assignment.hpp"
#include "tetrapulse/localizer/ring_buffer.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

// When a frame was exposed: [timestamp_ns, timestamp_ns + exposure_ns), rig time (frames.csv).
struct ExposureStamp {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;
  int64_t exposure_ns = 0;

  int64_t middle_ns() const { return timestamp_ns + exposure_ns / 2; }
};

struct TrackSample {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;  // exposure start, rig time
  int64_t exposure_ns = 0;
  // Blob::intensity when detected; RoiMeasurement::intensity for an ROI
  // measurement; 0 when nothing was measured (see `measured`). Grey levels x pixels.
  double intensity = 0;
  bool detected = false;  // a blob was found
  bool measured = false;  // `intensity` is a measurement (a blob, or an absent ROI's aperture)
  bool saturated = false; // some pixel of it clipped: `intensity` is compressed (a lower bound)
  bool merged = false;    // a part of a blob split between predicted markers (Blob::merged): not measured
  int merge_group = 0;    // merged: Blob::merge_group and merge_parts
  int merge_parts = 0;
  // Blob::bloomed: half the streak's length along the column (half its box's
  // height), pixels; 0 otherwise. Two-level codes bloom short in a 0 bit and long
  // in a 1, so the window around the next blob is sized by the longest recent one.
  double streak_half_px = 0;
  // The blob's centroid, or the position predicted for this frame when no blob
  // was found; pixels.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

inline constexpr size_t kTrackHistory = 64;

class BlobTrack {
 public:
  int64_t id() const { return id_; }
  // The newest kTrackHistory frames of this track, oldest first.
  const RingBuffer<TrackSample, kTrackHistory>& history() const { return history_; }
  const Blob& last_blob() const { return last_blob_; }  // the newest detected blob
  Eigen::Vector2d position() const { return last_blob_.centroid; }
  Eigen::Vector2d velocity_px_per_s() const { return velocity_; }
  int missed() const { return missed_; }        // consecutive frames without a blob, up to now
  int64_t detections() const { return detections_; }
  // Constant-velocity image position at rig time t_ns (pixels).
  Eigen::Vector2d predict(int64_t t_ns) const;

 private:
  friend class BlobTracker;
  int64_t id_ = 0;
  RingBuffer<TrackSample, kTrackHistory> history_;
  Blob last_blob_;
  int64_t last_detection_ns_ = 0;  // middle of that exposure
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero();
  int missed_ = 0;
  int64_t detections_ = 0;
  bool updated_ = false;  // in the frame being processed
};

// A caller's prediction for one track in the coming frame.
struct TrackGate {
  int64_t track_id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // pixels
  double radius = 0;                                    // pixels
};

struct BlobTrackerConfig {
  double gate_radius_px = 6;            // gate around the track's own prediction
  double gate_growth_px_per_frame = 2;  // added per coasted frame (the prediction drifts)
  // Frames a track survives without a blob. For on_off codes it must be at
  // least the longest run of 0 bits (in frames) + 1: see coast_frames_for().
  int max_coast_frames = 4;
};

// Longest cyclic run of 0 bits of `code` (its length when it has no 1).
int longest_zero_run(const Code& code);

// Longest run of frames (period frame_period_ns, exposure exposure_ns) in which
// `code` played on_off with bit period bit_period_ns is lit less than half of
// an exposure, over every phase of the code (sampled: 512 phases per code
// period, + 1 frame for a phase between them), at most `cap`. For codes whose
// bits are shorter than a frame (frequency codes) the dark frames come from
// aliasing, not from the length of a zero run.
int longest_dark_frames(const Code& code, int64_t bit_period_ns, int64_t frame_period_ns, int64_t exposure_ns,
                        int cap = 32);

// Coasting needed by the targets' codes when a frame lasts frame_period_ns:
// on_off modulation darkens a marker for its longest zero run, which spans
// ceil(run * bit_period / frame_period) frames; + 1 for a frame straddling
// the run's ends. With exposure_ns > 0, codes whose bits are shorter than a
// frame take longest_dark_frames() + 1 instead. 1 for two_level and constant
// modulation (markers never vanish). frame_period_ns <= 0 is read as one frame per bit.
int coast_frames_for(const TargetsFile& targets, int64_t frame_period_ns, int64_t exposure_ns = 0);

class BlobTracker {
 public:
  explicit BlobTracker(BlobTrackerConfig config = {});

  const BlobTrackerConfig& config() const { return config_; }
  // Coasting can be set once the frame period is known (coast_frames_for).
  void set_max_coast_frames(int frames) { config_.max_coast_frames = frames; }

  // One frame. First every ROI measurement whose tag names a live track is
  // that track's sample (detected or not: an absent ROI still brings its
  // measured intensity). Then the remaining tracks are matched to
  // extraction.blobs (the whole-image blobs, or the blobs no ROI took) within
  // their gates; `gates` overrides the prediction of the tracks it names.
  // Unmatched blobs start tracks; unmatched tracks coast or are deleted.
  // Frames must come in increasing rig time.
  void update(const ExposureStamp& frame, const BlobExtraction& extraction, const std::vector<TrackGate>& gates = {});

  const std::vector<BlobTrack>& tracks() const { return tracks_; }
  // The track with this id, nullptr when there is none (tracks() is in id order).
  const BlobTrack* find(int64_t id) const;
  // After update(): the track that took extraction.blobs[index] (an existing
  // track, or one it started), -1 when none did or the index is out of range.
  int64_t track_of_blob(size_t index) const {
    return index < blob_track_.size() ? blob_track_[index] : -1;
  }

  // An ROI per track for the frame exposed at `frame` (tag = track id),
  // centred on the track's prediction, of half side = its gate radius.
  void predict_rois(const ExposureStamp& frame, double aperture_radius, std::vector<BlobRoi>* rois) const;

 private:
  double gate_radius(const BlobTrack& track) const;
  // Index in tracks_ of the track with this id, tracks_.size() when there is none.
  size_t index_of(int64_t id) const;
  void add_detection(BlobTrack* track, const ExposureStamp& frame, const Blob& blob);
  void add_absence(BlobTrack* track, const ExposureStamp& frame, std::optional<double> intensity, bool saturated = false);

  BlobTrackerConfig config_;
  std::vector<BlobTrack> tracks_;
  int64_t next_id_ = 0;
  LinearAssignment assignment_;
  std::vector<double> cost_;
  std::vector<int> assigned_;
  std::vector<size_t> open_tracks_;
  std::vector<char> blob_taken_;
  std::vector<int64_t> blob_track_;
};

}  // namespace tetrapulse
