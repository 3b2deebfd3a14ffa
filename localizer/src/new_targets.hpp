#pragma once
// Internal to Localizer, stage 6 of a frame: targets not yet identified are
// looked for among the blob tracks no identified target owns
// (target_identifier.hpp), each at its blob this frame or, when dark now, at its
// own prediction. An identified target starts with the identification's markers,
// clock and pose (the seed its pose stage starts from this frame).
#include <cstdint>
#include <vector>

#include "code_reading.hpp"
#include "target_roster.hpp"
#include "tetrapulse/localizer/target_identifier.hpp"

namespace tetrapulse::localizer_internal {

class NewTargets {
 public:
  NewTargets(const CameraModel& camera, const TargetsFile& targets, const IdentificationOptions& options,
             bool frequency_coded);

  // Returns the targets identified in this frame (indices into TargetsFile::targets).
  std::vector<size_t> identify(const BlobTracker& tracker, CodeReading& reading, const ExposureStamp& stamp,
                               TargetRoster* roster);

 private:
  TargetIdentifier identifier_;
  bool frequency_coded_;
  int camera_width_, camera_height_;  // pixels
  std::vector<CandidateTrack> candidates_;
};

}  // namespace tetrapulse::localizer_internal
