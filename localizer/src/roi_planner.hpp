#pragma once
// Internal to Localizer, stage 1 of a frame: where to look.
//   - one ROI per blob track, at the track's own constant-velocity prediction
//     within its gate; for a track that is an identified target's marker, once
//     the target's pose has a velocity (two poses), where the predicted pose puts
//     the marker instead, widened to cover the track's own prediction too when a
//     recently seen track disagrees (the target turned since its last pose); that
//     prediction also gates the track in the tracker;
//   - one search ROI per marker of an identified target that has no track, where
//     the predicted pose puts it, when that lies in the image.
// Every ROI says what it is for (RoiPurpose): the tracker takes a track's ROI's
// measurement as that track's sample; a search ROI's blob is a new blob that its
// marker then claims. Pixels in the OpenCV convention; times in rig-time ns.
#include <cstdint>
#include <optional>
#include <vector>

#include "target_roster.hpp"
#include "tetrapulse/localizer/blob.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"

namespace tetrapulse::localizer_internal {

// A marker's track is predicted from its own motion this many frames after it was last seen.
inline constexpr int kMaxHintFrames = 2;

struct RoiPurpose {
  int64_t track_id = -1;            // the track whose ROI this is, or -1 for a search
  std::optional<MarkerRef> search;  // the marker a search ROI looks for
  int look = 0;                     // the look (Blob::look) of the track or of the marker searched for
  // Placed where a closely predicting target's pose puts its marker
  // (TargetRoster::predicts_closely), whose image radius is then known (pixels):
  // a blob outside the square and much larger is another light.
  bool exact = false;
  double marker_radius_px = 0;
};

struct RoiPlan {
  std::vector<BlobRoi> rois;        // BlobRoi::tag = the track id (-1 for a search)
  std::vector<RoiPurpose> purposes;  // one per ROI
  std::vector<TrackGate> gates;     // tracks gated by their target's predicted pose
};

// The aperture a track's next window needs around its blob (BlobRoi::aperture_radius),
// pixels: the spot's radius plus a margin, or for a bloomed marker half the
// longest streak it showed in the last 16 frames (a two_level 1 bit blooms longer
// than a 0), so that the window never cuts a streak's ends off: a cut end moves
// the centroid along the column by up to a pixel. A streak the last window cut
// (Blob::clipped) was longer than it looked, and the window grows by half again.
double aperture_radius_for(const BlobTrack& track);

void plan_rois(const TargetRoster& roster, const BlobTracker& tracker, const CameraModel& camera, int64_t mid_ns,
               int64_t frame_period_ns, double min_roi_radius_px, RoiPlan* plan);

}  // namespace tetrapulse::localizer_internal
