#pragma once
// Reading a blob track's samples as code bits: 1, 0 or unknown, with levels that
// adapt to each track. A marker's light changes with distance and angle far more
// than between its two levels within a few frames, so each sample is compared
// with the track's bright level around it, A: first the largest detected
// intensity within `window` samples either side; then, to follow light that
// grows or fades, the level interpolated between the nearest samples that read
// clearly as 1 on either side. With r = intensity / A and the modulation's
// relative 0 level `low` (0 for on_off):
//   r >= mid + band  -> 1,   r <= mid - band  -> 0,   otherwise unknown,
//   mid = (1 + low) / 2,  band = band_fraction (1 - low),
// and every sample is unknown while its window holds no detected blob, or (two
// levels) has not shown both levels (a run of equal bits longer than the
// window, or a track just born), or the sample was not measured
// (TrackSample::measured). An on-off 0 is dark: no level to learn. An
// exposure that straddles two bits of different value reads an intermediate
// level: unknown, or the value of the bit it mostly saw.
#include <array>
#include <cstddef>
#include <cstdint>

#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

enum class ReadBit : int8_t { kZero = 0, kOne = 1, kUnknown = -1 };

struct BitReading {
  int window = 8;             // samples either side
  double band_fraction = 0.15;
};

// One value per sample of a track's history (same indices).
using TrackBits = std::array<ReadBit, kTrackHistory>;

// Reads samples [from, history.size()) of `history` into bits[from..); the others
// are left as they are. Constant modulation reads every measured sample as 1.
void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits);

}  // namespace tetrapulse
