#include "code_checks.hpp"

#include <algorithm>

#include "tetrapulse/localizer/code_match.hpp"

namespace tetrapulse::localizer_internal {

CodeChecks::CodeChecks(const TargetsFile& targets, std::vector<std::array<int, 4>> frequency_of,
                       CodeCheckOptions options)
    : targets_(targets),
      frequency_of_(std::move(frequency_of)),
      options_(options),
      coded_(targets.modulation.kind != ModulationKind::kConstant),
      free_running_(coded_ && !targets.timebase.synchronized) {}

bool CodeChecks::has_binary_codes(size_t t) const {
  for (int m = 0; m < 4; ++m)
    if (targets_.targets[t].markers[size_t(m)].code && frequency_of_[t][size_t(m)] < 0) return true;
  return false;
}

bool followed_since(const BlobTrack& track, int64_t frame) {
  if (frame < 0) return false;
  const auto& h = track.history();
  for (size_t i = h.size(); i-- > 0;) {
    if (h[i].frame <= frame) return h[i].frame == frame && h[i].detected && !h[i].merged;
    if (h[i].merged) return false;  // its light was shared with another: it may have swapped
  }
  return false;  // older than the history: geometry must vouch again
}

bool CodeChecks::spans_code(const BlobTrack& track, const Code& code, size_t from) const {
  const auto& h = track.history();
  return h.size() > from &&
         h.newest().timestamp_ns - h[from].timestamp_ns >= int64_t(code.length - 1) * targets_.timebase.bit_period_ns;
}

void CodeChecks::refit_clock(const BlobTracker& tracker, const CodeReading& reading, size_t t, int64_t mid_ns,
                             TrackedTarget* tt) const {
  const Target& target = targets_.targets[t];
  uint32_t length = 1;
  for (const Marker& m : target.markers)
    if (m.code) length = std::max<uint32_t>(length, m.code->length);
  tt->clock.refit(mid_ns, length, [&](const CodeClock& clock) {
    double cost = 0;
    for (int m = 0; m < 4; ++m) {
      const BlobTrack* track = tracker.find(tt->track_of[size_t(m)]);
      if (!track || !target.markers[size_t(m)].code || frequency_of_[t][size_t(m)] >= 0) continue;
      cost += match_code(track->history(), reading.bits(track->id()),
                         CodeReading::first_of_newest(*track, options_.clock_samples), clock,
                         *target.markers[size_t(m)].code)
                  .cost();
    }
    return cost;
  });
}

void CodeChecks::check(const BlobTracker& tracker, CodeReading& reading, int64_t frame, int64_t mid_ns,
                       TargetRoster* roster) const {
  if (!coded_) return;
  for (size_t t = 0; t < roster->size(); ++t) {
    TrackedTarget& tt = (*roster)[t];
    if (!tt.identified) continue;
    if (free_running_ && has_binary_codes(t)) refit_clock(tracker, reading, t, mid_ns, &tt);
    for (int m = 0; m < 4; ++m) {
      const Marker& marker = targets_.targets[t].markers[size_t(m)];
      const BlobTrack* track = tracker.find(tt.track_of[size_t(m)]);
      if (!track || !marker.code) continue;
      if (const int expected = frequency_of_[t][size_t(m)]; expected >= 0) {
        if ((frame + track->id()) % std::max(1, options_.frequency_check_frames) != 0) continue;
        const FrequencyDecision* d = reading.frequency_decision(track->id());
        if (d && d->decided() && (d->kind != FrequencyDecision::Kind::kFrequency || d->code != expected))
          tt.release(m);
        else if (d && d->kind == FrequencyDecision::Kind::kFrequency)
          tt.confirmed[size_t(m)] = true;
        continue;
      }
      const size_t from = CodeReading::first_of_newest(*track, options_.verify_samples);
      const CodeMatch match = match_code(track->history(), reading.bits(track->id()), from, tt.clock.fitted(),
                                         *marker.code);
      if (match.mismatches > options_.verify_max_errors) {
        if (!followed_since(*track, tt.vouched_frame[size_t(m)])) tt.release(m);
      } else if (!tt.confirmed[size_t(m)] && match.counted >= int(marker.code->length) &&
                 match.mismatches <= match.counted / 16 && spans_code(*track, *marker.code, from)) {
        tt.confirmed[size_t(m)] = true;  // a whole code cycle read: another code would differ somewhere
      }
    }
  }
}

}  // namespace tetrapulse::localizer_internal
