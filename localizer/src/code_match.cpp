#include "tetrapulse/localizer/code_match.hpp"

namespace tetrapulse {

namespace {

void compare(ExpectedBit expected, ReadBit read, CodeMatch* m) {
  if (read == ReadBit::kUnknown) return;
  if (expected == ExpectedBit::kMixed) {
    ++m->unexplained;
    return;
  }
  ++m->counted;
  m->mismatches += (expected == ExpectedBit::kOne) != (read == ReadBit::kOne);
}

}  // namespace

CodeMatch match_code(const RingBuffer<TrackSample, kTrackHistory>& history, const TrackBits& bits, size_t from,
                     const CodeClock& clock, const Code& code) {
  CodeMatch m;
  for (size_t j = from; j < history.size(); ++j) {
    if (bits[j] == ReadBit::kUnknown) continue;
    const TrackSample& s = history[j];
    compare(expected_bit(clock, code, s.timestamp_ns, s.exposure_ns), bits[j], &m);
  }
  return m;
}

int64_t phase_origin(int64_t base_origin_ns, int64_t bit_period_ns, int steps, int g) {
  return base_origin_ns + (bit_period_ns * g) / steps;
}

void match_code_phases(const RingBuffer<TrackSample, kTrackHistory>& history, const TrackBits& bits, size_t from,
                       int64_t base_origin_ns, int64_t bit_period_ns, int steps, const Code& code,
                       std::vector<CodeMatch>* out) {
  const int phases = int(code.length) * steps;
  out->assign(size_t(phases), CodeMatch{});
  for (size_t j = from; j < history.size(); ++j) {
    if (bits[j] == ReadBit::kUnknown) continue;
    const TrackSample& s = history[j];
    for (int g = 0; g < phases; ++g) {
      const CodeClock clock{phase_origin(base_origin_ns, bit_period_ns, steps, g), bit_period_ns, 1.0};
      compare(expected_bit(clock, code, s.timestamp_ns, s.exposure_ns), bits[j], &(*out)[size_t(g)]);
    }
  }
}

}  // namespace tetrapulse
