#pragma once
// The localizer: images in, identified 6D poses out (Breitenmoser, Kneip &
// Siegwart 2011, Sec. IV, with temporal codes). A frame runs these stages, each
// a file of its own under src/ (localizer.cpp reads top to bottom):
//   1. prediction and ROI planning (target_roster, roi_planner): each identified
//      target's pose at mid-exposure (pose_predictor.hpp), projected into its
//      markers' pixels; an ROI per blob track and a search ROI per marker that
//      has no track;
//   2. blobs (frame_blobs; blob_extractor.hpp) in those ROIs, with the fallbacks
//      a tracked scene needs, and the whole image on the first frame and in
//      bursts every full_search_interval frames while some target, or some
//      marker of an identified target, is not tracked;
//   3. tracks (blob_tracker.hpp), whose samples carry each marker's light; new
//      tracks at a missing marker's predicted pixel rejoin it (marker_tracks);
//   4. code reading (code_reading; track_bits.hpp, frequency_identifier.hpp):
//      bits of every track, and the square wave of a track's exposure-integrated
//      light when the rig has frequency codes;
//   5. code checks (code_checks): an identified target's tracks keep being
//      checked against their codes, under its board's clock (target_clock: the
//      free-running estimate), and leave it when they stop matching;
//   6. identification (new_targets; target_identifier.hpp): codes and geometry
//      together name targets and markers among the tracks nobody owns;
//   7. pose (target_poses; marker_pose.hpp) from the identified markers seen this
//      frame, from the prediction — in the frame a target is identified, the
//      identification's refined pose.
// Knows nothing of boards, buses or file formats: only pixels, the targets and
// the rig timestamps of exposures. Poses as pose.hpp (p_C = R p_T + t, metres,
// OpenCV camera frame); times in integer nanoseconds of rig time. Not thread-safe.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <tl/expected.hpp>

#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/frequency_identifier.hpp"
#include "tetrapulse/localizer/marker_pose.hpp"
#include "tetrapulse/localizer/pose_predictor.hpp"
#include "tetrapulse/localizer/target_identifier.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/localizer/track_bits.hpp"

namespace tetrapulse {

struct LocalizerOptions {
  P3PSolver p3p = kDefaultP3PSolver;
  PredictionOptions prediction;     // k_R = 2 linear regression by default
  MarkerPoseOptions pose;           // sphere-centroid model on, max RMS 1.5 px
  IdentificationOptions identification;
  BitReading bits;
  FrequencyIdentifierOptions frequency;  // tracks of frequency codes
  int frequency_check_frames = 8;        // a claimed frequency track's code is checked this often
  BlobExtractorConfig blobs;
  // Whole-image search every this many frames while something is not tracked.
  int full_search_interval = 4;
  double min_roi_radius_px = 6;     // ROI half side around a predicted marker, at least
  // Code verification of a tracked target's tracks: the newest verify_samples
  // samples may hold at most verify_max_errors read errors.
  int verify_samples = 24;
  int verify_max_errors = 3;
  // A marker left out of the pose this many frames in a row leaves its target.
  int max_outlier_frames = 3;
  // A target without a pose for this long is forgotten (identified anew later), ns.
  int64_t forget_after_ns = 500'000'000;
};

struct TargetPose {
  int target_id = 0;
  int64_t mid_exposure_ns = 0;  // rig time the pose holds at: the middle of the frame's exposure
  Pose pose;
  PoseStatus status = PoseStatus::kAllMarkers;
  int markers = 0;       // markers the pose used
  double rms_px = 0;     // their RMS reprojection error
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();  // of (w, v), pose_refinement.hpp
  bool has_covariance = false;
};

struct LocalizerError {
  std::string message;  // "image is 640x480, the camera 752x480"
};

// Where a track stands, for overlays and diagnostics.
struct TrackLabel {
  int64_t track_id = 0;
  int target_id = -1;  // -1: not identified
  int marker = -1;
};

class Localizer {
 public:
  Localizer(const CameraInfo& camera, const TargetsFile& targets, LocalizerOptions options = {});
  ~Localizer();
  Localizer(Localizer&&) noexcept;
  Localizer& operator=(Localizer&&) noexcept;

  // One frame exposed over [exposure_start_ns, + exposure_ns) of rig time; frames
  // must come in increasing time. Image: camera-sized 8- or 16-bit grey (or 8-bit
  // BGR). Returns the identified targets' poses at mid-exposure.
  tl::expected<std::vector<TargetPose>, LocalizerError> process(const cv::Mat& image, int64_t exposure_start_ns,
                                                                int64_t exposure_ns);

  const CameraModel& camera() const;
  const TargetsFile& targets() const;
  // What the last frame saw: blobs of the ROIs and of the whole image.
  const BlobExtraction& extraction() const;
  const BlobTracker& tracker() const;
  std::vector<TrackLabel> track_labels() const;
  bool searched_whole_image() const;  // in the last frame
  // Whether poses model the markers' centroids as sphere images (sphere_image.hpp)
  // or as their centres' projections: decided by a sequential test over the first
  // 100-1000 clean four-marker poses (the model the rig's images fit; centroid_model.hpp).
  bool measures_sphere_images() const;
  // Free-running boards: the estimated clock of a tracked target (nullopt when not tracked).
  std::optional<CodeClock> clock_of(int target_id) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tetrapulse
