#pragma once
// Internal to Localizer, stage 7 of a frame: each identified target's pose from
// its markers seen this frame (marker_pose.hpp), started from its predicted pose
// — in the frame it is identified, the identification's refined pose; that frame's
// pose must fit within 4x the rig's centroid noise (TargetRoster::rig_rms_px),
// with no three markers standing in, else the first pose waits a frame.
//   - Four markers seen: one pose of all four, or (one not fitting) of three.
//   - A marker whose track is not confirmed yet (target_roster.hpp) takes part
//     only in a pose of all four that it fits (two such fits confirm it); else
//     the pose comes from the confirmed markers alone.
//   - Three markers: P3P's roots told apart by a dark marker's hint (its track's
//     own motion), by the light a lit marker's code says should be where a root
//     puts it, or by the prediction (marker_pose.hpp); never a root far from the
//     prediction, and nothing when the ambiguity stays. Such a pose must agree
//     with the prediction within a gate that grows with the frames since the last
//     pose, unless the dark marker's own track picked the root.
//   - No pose from its tracks: the blobs around it, assigned afresh, when exactly
//     one assignment fits all four (marker_reassociation.hpp); it then owns them.
// The prediction is trusted less the further it extrapolates. Then the
// bookkeeping a pose brings: a marker left out max_outlier_frames in a row
// leaves the target; the prediction's running error; the predictor's history.
// A target that holds no track is forgotten at once (identification finds it
// again within a code length), else after forget_after_ns without a pose.
#include <array>
#include <cstdint>
#include <optional>

#include "centroid_model.hpp"
#include "target_roster.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace tetrapulse::localizer_internal {

struct TargetPoseOptions {
  MarkerPoseOptions pose;
  int max_outlier_frames = 3;
  int64_t forget_after_ns = 500'000'000;
};

// The frame the poses are solved in.
struct PoseFrame {
  const CameraModel& camera;
  const TargetsFile& targets;
  const BlobTracker& tracker;
  const ExposureStamp& stamp;
  int64_t frame_period_ns = 0;  // 0: not known yet
};

// frequency_of: per marker of target t, its frequency code (>= 0) or -1.
// centroids: the centroid model the poses use, weighed by each clean four-marker pose.
std::optional<TargetPose> solve_target_pose(const PoseFrame& frame, size_t t, const std::array<int, 4>& frequency_of,
                                            const TargetPoseOptions& options, TargetRoster* roster,
                                            CentroidModel* centroids);

}  // namespace tetrapulse::localizer_internal
