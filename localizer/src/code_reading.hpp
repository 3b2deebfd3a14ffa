#pragma once
// Internal to Localizer, stage 4 of a frame: what each blob track's light says.
//   - bits (track_bits.hpp): every track's newest max(identification
//     max_samples, verify_samples) samples kept current; identification reads
//     unclaimed tracks, code checks claimed ones (a free-running clock's refit
//     all of them). A reader re-reads only the newest samples, whose bits can
//     still change, so keeping all current costs no more than keeping some.
//   - frequencies (frequency_identifier.hpp): when the rig has frequency codes,
//     each track's exposure-integrated light, from which its square wave is told.
// State ends with its track.
#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/frequency_identifier.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/localizer/track_bits.hpp"

namespace tetrapulse::localizer_internal {

class CodeReading {
 public:
  // `samples`: how many of each track's newest samples are read.
  CodeReading(const TargetsFile& targets, const BitReading& reading, const FrequencyIdentifierOptions& frequency,
              int samples, bool frequency_coded);

  // After the tracker's update for the frame numbered `frame`.
  void update(const BlobTracker& tracker, int64_t frame);

  // The read bits of a track's history (all unknown for a track never read).
  const TrackBits& bits(int64_t track_id) const;
  // The first sample index of a track's newest `samples`.
  static size_t first_of_newest(const BlobTrack& track, int samples);
  // The frequency code (rig_codes() index) a track carries, -1 while none is decided or it is no frequency code.
  int frequency_code(int64_t track_id);
  // The frequency decision over a track's light (nullptr: none kept).
  const FrequencyDecision* frequency_decision(int64_t track_id);

 private:
  const TargetsFile& targets_;
  BitReading reading_;
  FrequencyIdentifierOptions frequency_options_;
  int samples_;
  bool coded_;
  bool frequency_coded_;
  std::unordered_map<int64_t, TrackBitReader> bits_;
  std::unordered_map<int64_t, FrequencyIdentifier> frequencies_;
};

}  // namespace tetrapulse::localizer_internal
