#include "tetrapulse/localizer/track_bits.hpp"

#include <algorithm>
#include <array>

namespace tetrapulse {

void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits) {
  const size_t n = history.size();
  const double low = modulation.kind == ModulationKind::kTwoLevel ? modulation.low : 0.0;
  const double mid = (1 + low) / 2, band = reading.band_fraction * (1 - low);
  const size_t w = size_t(std::max(reading.window, 1));
  // Pass 1 reads against the brightest detected sample within the window (any
  // sample that can influence samples from `from` on). Pass 2 reads against the
  // bright level interpolated between the nearest clear 1s before and after: a
  // marker whose light grows or fades within the window is then still read.
  const size_t first = from > 2 * w ? from - 2 * w : 0;
  std::array<double, kTrackHistory> bright{};
  std::array<ReadBit, kTrackHistory> pass1{};
  for (size_t j = first; j < n; ++j) {
    pass1[j] = ReadBit::kUnknown;
    bright[j] = 0;
    const TrackSample& s = history[j];
    if (!s.measured) continue;
    if (modulation.kind == ModulationKind::kConstant) {
      pass1[j] = ReadBit::kOne;
      continue;
    }
    // The window around j; near the newest sample it extends further back, so
    // that it always spans 2w + 1 samples.
    const size_t hi_end = std::min(n, j + w + 1);
    const size_t lo_begin = hi_end >= 2 * w + 1 ? hi_end - (2 * w + 1) : 0;
    double top = 0, dim = 0;
    bool any_detected = false, any = false;
    for (size_t k = lo_begin; k < hi_end; ++k) {
      const TrackSample& o = history[k];
      if (!o.measured) continue;
      if (o.detected && (!any_detected || o.intensity > top)) top = o.intensity, any_detected = true;
      dim = any ? std::min(dim, o.intensity) : o.intensity;
      any = true;
    }
    if (!any_detected || !(top > 0)) continue;
    // Two levels: both must have been seen (the dimmest sample reads as a 0), or
    // a run of 1s would read as 0s and a run of 0s as 1s. An on-off 0 is dark,
    // a level known without seeing it.
    if (modulation.kind == ModulationKind::kTwoLevel && !(dim <= top * (mid - band))) continue;
    bright[j] = top;
    const double r = s.intensity / top;
    pass1[j] = r >= mid + band ? ReadBit::kOne : r <= mid - band ? ReadBit::kZero : ReadBit::kUnknown;
  }
  for (size_t j = from; j < n; ++j) {
    ReadBit& out = (*bits)[j];
    out = pass1[j];
    if (modulation.kind == ModulationKind::kConstant || !(bright[j] > 0)) continue;
    // The nearest clear 1s on each side within the window.
    int before = -1, after = -1;
    for (size_t k = j + 1; k-- > (j >= w ? j - w : 0);)
      if (pass1[k] == ReadBit::kOne && history[k].detected) {
        before = int(k);
        break;
      }
    for (size_t k = j; k < std::min(n, j + w + 1); ++k)
      if (pass1[k] == ReadBit::kOne && history[k].detected) {
        after = int(k);
        break;
      }
    double level = bright[j];
    if (before >= 0 && after >= 0 && after != before) {
      const double a = history[size_t(before)].intensity, b = history[size_t(after)].intensity;
      level = a + (b - a) * double(int(j) - before) / double(after - before);
    } else if (before >= 0 || after >= 0) {
      level = history[size_t(before >= 0 ? before : after)].intensity;
    }
    if (!(level > 0)) continue;
    const double r = history[j].intensity / level;
    out = r >= mid + band ? ReadBit::kOne : r <= mid - band ? ReadBit::kZero : ReadBit::kUnknown;
  }
}

}  // namespace tetrapulse
