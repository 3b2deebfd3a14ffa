#pragma once
// Measured poses (poses.csv) against a dataset's ground truth (groundtruth.csv).
//
// Errors: position |t - t_true| (m) and orientation angle of R_true^T R (rad),
// per target and over all, for every reported row whose target has a true pose
// in that frame.
// Visible: a target in a frame whose true pose puts at least three markers lit
// and in view. In view: the marker's centre projects into the image, at least
// its image radius inside the border. Lit: the contract's mean emission over the
// exposure (code_clock.hpp) is at least half of full, or the modulation is
// two_level or constant (a 0 bit still shines), or the boards run free (their
// phase is unknown, so on_off markers count as lit) unless the evaluation is
// given the boards' true clocks (EvaluationOptions::board_clocks: a simulation
// knows them), which then say when a marker is lit. Occlusions are not in a
// dataset: an occluded marker counts as visible.
// Identification latency: frames from the start of each episode of visibility
// (a visible frame after more than `episode_gap_frames` frame numbers without
// one, or the first) to the first frame reported in it; an episode never
// reported is counted as its whole length.
// Coverage: visible frames with a reported pose / visible frames, counted from
// each episode's first report on (the frames before are its latency, reported
// as such); an episode never reported counts whole.
// Misidentification: a row naming a target that is not in targets.yaml, that has
// no true pose in that frame, or whose pose is further from that target's true
// pose than gross_position (absolute or relative to the distance) or
// gross_orientation: the pose of something else.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/localizer/code_clock.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace tetrapulse {

struct ErrorStats {
  size_t count = 0;
  double mean = 0, median = 0, p95 = 0, max = 0;

  static ErrorStats of(std::vector<double> values);
};

struct TargetEvaluation {
  int target = -1;            // -1: all targets
  ErrorStats position_m;
  ErrorStats orientation_rad;
  size_t rows = 0;            // rows reported
  size_t visible_frames_total = 0;  // visible frames
  size_t visible_frames = 0;        // of those, from each episode's first report on
  size_t covered_frames = 0;        // of those, frames with a row
  size_t misidentified = 0;
  size_t episodes = 0;
  std::optional<int64_t> first_latency_frames;  // of the first episode
  int64_t max_latency_frames = 0;               // over all episodes

  double coverage() const { return visible_frames ? double(covered_frames) / double(visible_frames) : 1.0; }
};

struct EvaluationOptions {
  double gross_position_m = 0.05;
  double gross_position_relative = 0.1;  // of the target's distance
  double gross_orientation_rad = 20 * M_PI / 180;
  int64_t episode_gap_frames = 0;        // 0: one code length in frames (at least 10)
  // True code clocks of free-running boards, by target id (rig time to bits as
  // code_clock.hpp); targets not in it count their on_off markers as lit.
  std::map<int, CodeClock> board_clocks;
};

struct Evaluation {
  std::vector<TargetEvaluation> targets;  // in targets.yaml order
  TargetEvaluation overall;
  int64_t episode_gap_frames = 0;
};

// Fails when the dataset has no ground truth, or a row names a frame that is not
// in frames.csv (the error names the poses file).
DatasetResult<Evaluation> evaluate_poses(const RigDataset& dataset, const std::vector<PoseRecord>& poses,
                                         const std::string& poses_name, const EvaluationOptions& options = {});

// How many of a target's markers are lit and in view (as above) under `pose`
// during [start_ns, start_ns + exposure_ns); `board_clock`: the board's true
// clock when known (free-running boards).
int markers_lit_in_view(const CameraModel& camera, const TargetsFile& targets, const Target& target,
                        const Pose& pose, int64_t start_ns, int64_t exposure_ns,
                        const CodeClock* board_clock = nullptr);

}  // namespace tetrapulse
