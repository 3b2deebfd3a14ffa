#pragma once
// How well a code explains a track's bits (track_bits.hpp) under a code clock
// (code_clock.hpp): each read bit is compared with the bit the code plays during
// that sample's exposure. Exposures over bits of both values are not counted;
// a clean reading there is `unexplained` (the clock puts an edge where the
// light saw none), which free-running phase search weighs against a phase.
#include <cstddef>
#include <vector>

#include "tetrapulse/localizer/code_clock.hpp"
#include "tetrapulse/localizer/track_bits.hpp"

namespace tetrapulse {

struct CodeMatch {
  int counted = 0;      // read bits compared with a clean expected bit
  int mismatches = 0;   // of those, how many differ
  int unexplained = 0;  // read bits where the code expects a mixed exposure

  // Mismatches, plus half an error per unexplained clean reading.
  double cost() const { return mismatches + 0.5 * unexplained; }
  CodeMatch& operator+=(const CodeMatch& o) {
    counted += o.counted, mismatches += o.mismatches, unexplained += o.unexplained;
    return *this;
  }
};

// Samples [from, history.size()) of a track against `code` under `clock`.
CodeMatch match_code(const RingBuffer<TrackSample, kTrackHistory>& history, const TrackBits& bits, size_t from,
                     const CodeClock& clock, const Code& code);

// The same for `code.length * steps` clocks of rate 1 whose origins are
// base_origin_ns + g T / steps, g = 0, 1, ...: every phase of the code, for
// boards whose phase is unknown. out[g] is the match at origin g.
void match_code_phases(const RingBuffer<TrackSample, kTrackHistory>& history, const TrackBits& bits, size_t from,
                       int64_t base_origin_ns, int64_t bit_period_ns, int steps, const Code& code,
                       std::vector<CodeMatch>* out);

// Origin of phase g of match_code_phases.
int64_t phase_origin(int64_t base_origin_ns, int64_t bit_period_ns, int steps, int g);

}  // namespace tetrapulse
