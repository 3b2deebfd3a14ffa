#include "tetrapulse/localizer/track_bits.hpp"

#include <algorithm>

namespace tetrapulse {

void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits) {
  const size_t n = history.size();
  const double low = modulation.kind == ModulationKind::kTwoLevel ? modulation.low : 0.0;
  const double mid = (1 + low) / 2, band = reading.band_fraction * (1 - low);
  const size_t w = size_t(std::max(reading.window, 1));
  for (size_t j = from; j < n; ++j) {
    ReadBit& out = (*bits)[j];
    out = ReadBit::kUnknown;
    const TrackSample& s = history[j];
    if (!s.measured) continue;
    if (modulation.kind == ModulationKind::kConstant) {
      out = ReadBit::kOne;
      continue;
    }
    // The bright level A and the dimmest measured sample around j. Near the newest
    // sample the window extends further back, so that it always spans 2w + 1 samples.
    const size_t hi_end = std::min(n, j + w + 1);
    const size_t lo_begin = hi_end >= 2 * w + 1 ? hi_end - (2 * w + 1) : 0;
    double bright = 0, dim = 0;
    bool any_detected = false, any = false;
    for (size_t k = lo_begin; k < hi_end; ++k) {
      const TrackSample& o = history[k];
      if (!o.measured) continue;
      if (o.detected && (!any_detected || o.intensity > bright)) bright = o.intensity, any_detected = true;
      dim = any ? std::min(dim, o.intensity) : o.intensity;
      any = true;
    }
    if (!any_detected || !(bright > 0)) continue;
    // Two levels: both must have been seen (the dimmest sample reads as a 0), or
    // a run of 1s would read as 0s and a run of 0s as 1s. An on-off 0 is dark,
    // a level known without seeing it.
    if (modulation.kind == ModulationKind::kTwoLevel && !(dim <= bright * (mid - band))) continue;
    const double r = s.intensity / bright;
    if (r >= mid + band) {
      out = ReadBit::kOne;
    } else if (r <= mid - band) {
      out = ReadBit::kZero;
    }
  }
}

}  // namespace tetrapulse
