#include "new_targets.hpp"

namespace tetrapulse::localizer_internal {

NewTargets::NewTargets(const CameraModel& camera, const TargetsFile& targets, const IdentificationOptions& options,
                       bool frequency_coded)
    : identifier_(camera, targets, options),
      frequency_coded_(frequency_coded),
      camera_width_(camera.width()),
      camera_height_(camera.height()) {}

std::vector<size_t> NewTargets::identify(const BlobTracker& tracker, CodeReading& reading, const ExposureStamp& stamp,
                                         TargetRoster* roster) {
  std::vector<size_t> found;
  std::vector<bool> wanted(roster->size());
  bool any = false;
  for (size_t t = 0; t < roster->size(); ++t) any |= (wanted[t] = !(*roster)[t].identified);
  if (!any) return found;
  candidates_.clear();
  for (const BlobTrack& track : tracker.tracks()) {
    if (roster->owner(track.id())) continue;
    CandidateTrack c;
    c.track = &track;
    c.bits = &reading.bits(track.id());
    const TrackSample& newest = track.history().newest();
    const bool seen = newest.frame == stamp.frame && newest.detected;
    c.pixel = seen ? newest.centroid : track.predict(stamp.middle_ns());
    c.measured = seen && !newest.merged && !cut_by_border(track.last_blob(), camera_width_, camera_height_);
    c.radius_px = track.last_blob().radius;
    c.look = track.last_blob().look;
    if (frequency_coded_) c.frequency_code = reading.frequency_code(track.id());
    candidates_.push_back(c);
  }
  if (candidates_.size() < 3) return found;  // three: a marker may be out of view
  for (const Identification& id : identifier_.identify(candidates_, wanted)) {
    (*roster)[id.target].identify(id.track_of, id.clock, id.pose, id.rms_px, stamp.middle_ns());
    found.push_back(id.target);
  }
  return found;
}

}  // namespace tetrapulse::localizer_internal
