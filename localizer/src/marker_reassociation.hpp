#pragma once
// Internal to Localizer, stage 7: an identified target whose tracks gave no pose
// this frame, or only a three-marker one while a fourth blob of it was in sight,
// fitted again to the blobs around it. When a target stops or turns short while
// its markers are dark, every track overshoots its blob by the same image shift,
// and a track can take the blob of the marker beside it (the others' three-marker
// roots then lie far from the prediction, and are refused). The target's markers
// moved as one body, so the assignment of this frame's blobs to its markers that
// the prediction's projections fit under one common shift, and that four-marker
// pose fits, is the right one — when it is the only one.
//   Candidates: whole blobs detected this frame (not merged, not cut by the
//   image's border) on tracks this target owns or nobody owns, within kReachPx of
//   one of its predicted marker pixels; the nearest kMaxCandidates. Each
//   assignment of four of them to the four markers whose shifts (blob - predicted
//   pixel) agree within 3 px + 0.15 x the predicted pattern's span is solved
//   (solve_marker_pose, four markers); it fits when its RMS is within
//   `options.max_rms_px` and it lies within `max_distance` of the prediction
//   (pose_distance). Exactly one fitting assignment is returned.
// Pixels in the OpenCV convention; poses as pose.hpp.
#include <array>
#include <cstdint>
#include <optional>

#include "target_poses.hpp"

namespace tetrapulse::localizer_internal {

inline constexpr double kReachPx = 40;
inline constexpr size_t kMaxCandidates = 6;

struct Reassociation {
  std::array<int64_t, 4> tracks{};  // each marker's track
  MarkerPose pose;                  // of all four
};

std::optional<Reassociation> reassociate(const PoseFrame& frame, size_t t, const TargetRoster& roster,
                                         const MarkerPoseOptions& options, double max_distance);

}  // namespace tetrapulse::localizer_internal
