#include "marker_tracks.hpp"

namespace tetrapulse::localizer_internal {
namespace {

bool newborn(const BlobTrack& track) { return track.detections() == 1 && track.history().size() == 1; }

}  // namespace

void claim_new_tracks(const BlobTracker& tracker, const std::vector<SearchHit>& hits, int64_t mid_ns,
                      int64_t frame_period_ns, TargetRoster* roster) {
  TargetRoster& r = *roster;
  for (const SearchHit& hit : hits) {
    TrackedTarget& tt = r[hit.marker.target];
    if (!tt.identified || tt.track_of[size_t(hit.marker.marker)] >= 0) continue;
    const BlobTrack* track = tracker.find(tracker.track_of_blob(hit.blob));
    if (track && newborn(*track) && !r.owner(track->id())) tt.assign(hit.marker.marker, track->id());
  }
  for (size_t t = 0; t < r.size(); ++t) {
    TrackedTarget& tt = r[t];
    if (!tt.identified) continue;
    for (int m = 0; m < 4; ++m) {
      Eigen::Vector2d px;
      if (tt.track_of[size_t(m)] >= 0 || !r.project_marker(t, m, &px)) continue;
      const double gate = r.roi_radius(t, mid_ns, frame_period_ns) + 2;
      int64_t found = -1;
      int count = 0;
      for (const BlobTrack& track : tracker.tracks())
        if (newborn(track) && track.last_blob().look == r.look_of(t, m) && (track.position() - px).norm() <= gate &&
            !r.owner(track.id()))
          found = track.id(), ++count;
      if (count == 1) tt.assign(m, found);
    }
  }
}

}  // namespace tetrapulse::localizer_internal
