#pragma once
// Internal to Localizer, stage 7 of a frame: each identified target's pose from
// its markers seen this frame (marker_pose.hpp), started from its predicted pose
// — in the frame it is identified, the identification's refined pose. A marker
// dark this frame whose track was seen lately hints where it is (its track's
// own motion). The prediction is trusted less the further it extrapolates.
// Then the bookkeeping a pose brings: a marker left out max_outlier_frames in a
// row leaves the target; the prediction's running error; the predictor's
// history. A target without a pose for forget_after_ns is forgotten.
#include <cstdint>
#include <optional>

#include "target_roster.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace tetrapulse::localizer_internal {

struct TargetPoseOptions {
  MarkerPoseOptions pose;
  int max_outlier_frames = 3;
  int64_t forget_after_ns = 500'000'000;
};

std::optional<TargetPose> solve_target_pose(const CameraModel& camera, const Target& target, size_t t,
                                            const BlobTracker& tracker, const ExposureStamp& stamp,
                                            int64_t frame_period_ns, const TargetPoseOptions& options,
                                            TargetRoster* roster);

}  // namespace tetrapulse::localizer_internal
