#pragma once
// Internal to Localizer, stage 5 of a frame: an identified target's tracks keep
// being checked against their markers' codes.
//   - binary codes: the newest verify_samples samples under the target's clock
//     may hold at most verify_max_errors read errors; a track with more leaves
//     its marker, unless geometry vouched for it (it was one of four markers
//     fitting one pose, TrackedTarget::vouched_frame) and it has been followed
//     without a merge since: an isolated blob followed from frame to frame does
//     not change identity, while codes can become unreadable (both levels of a
//     close marker clip). A track that joined its marker after the identification is
//     confirmed once a whole code length of read bits matches (at most one
//     error in 16). Free-running boards first have their clock's origin re-fitted
//     (target_clock.hpp) once per code length, over the tracks' newest `samples`.
//   - frequency codes are judged over the whole window, so now and then
//     (every frequency_check_frames frames, staggered by track): a track that now
//     carries another code, or a binary one, leaves its marker.
#include <array>
#include <cstdint>
#include <vector>

#include "code_reading.hpp"
#include "target_roster.hpp"

namespace tetrapulse::localizer_internal {

struct CodeCheckOptions {
  int verify_samples = 24;
  int verify_max_errors = 3;
  int frequency_check_frames = 8;
  int clock_samples = 48;  // samples a free-running clock is re-fitted over
};

// Whether the track holds the sample of `frame` (detected, unmerged) and no
// merged sample after it. frame < 0: false.
bool followed_since(const BlobTrack& track, int64_t frame);

class CodeChecks {
 public:
  // frequency_of: per target and marker, the rig_codes() index of its frequency code (-1: binary or none).
  CodeChecks(const TargetsFile& targets, std::vector<std::array<int, 4>> frequency_of, CodeCheckOptions options);

  void check(const BlobTracker& tracker, CodeReading& reading, int64_t frame, int64_t mid_ns, TargetRoster* roster) const;

  // Whether some marker of target t plays a binary code.
  bool has_binary_codes(size_t t) const;
  const std::array<int, 4>& frequency_of(size_t t) const { return frequency_of_[t]; }

 private:
  // Whether samples [from, end) of the track span a whole cycle of `code`.
  bool spans_code(const BlobTrack& track, const Code& code, size_t from) const;
  void refit_clock(const BlobTracker& tracker, const CodeReading& reading, size_t t, int64_t mid_ns,
                   TrackedTarget* tt) const;

  const TargetsFile& targets_;
  std::vector<std::array<int, 4>> frequency_of_;
  CodeCheckOptions options_;
  bool coded_;
  bool free_running_;
};

}  // namespace tetrapulse::localizer_internal
