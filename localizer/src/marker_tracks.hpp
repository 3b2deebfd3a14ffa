#pragma once
// Internal to Localizer, stage 3 of a frame (after the tracker's update): which
// new blob tracks become markers of identified targets.
//   - a track started by a search ROI's blob joins the marker it was searched for;
//   - a new track from the whole image within the target's ROI radius (+ 2 px) of
//     a missing marker's predicted pixel joins that marker when it is the only one
//     there.
// Either is then checked against the marker's code like every claimed track.
#include <cstdint>
#include <vector>

#include "frame_blobs.hpp"
#include "target_roster.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"

namespace tetrapulse::localizer_internal {

void claim_new_tracks(const BlobTracker& tracker, const std::vector<SearchHit>& hits, int64_t mid_ns,
                      int64_t frame_period_ns, TargetRoster* roster);

}  // namespace tetrapulse::localizer_internal
