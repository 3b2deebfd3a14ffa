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
// Two levels whose light does not keep the nominal ratio — a saturated marker,
// whose clipped 1 gains only a ring of pixels over its 0, or a camera whose
// response is not linear (gamma-encoded video) — are learned from the window
// itself: the widest gap between the sorted logarithms of its detected
// intensities splits 0s from 1s when it is at least a ratio of 1.04, at least
// twice the spread on either side, with two samples or more on each side (a
// drifting level spreads values evenly, a code splits them into two tight
// groups), after a common drift of the logarithms (a parabola fitted with the
// bits) is taken out; mid is then the gap's middle and band a quarter of it.
// A window with a saturated sample reads this way when it can; one whose 0s
// the nominal levels cannot read (or leave unknown) too.
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

// Where a sample's ratio r to its bright level reads: r >= mid + band -> 1,
// r <= mid - band -> 0, unknown between.
struct BitSplit {
  double mid = 0, band = 0;

  ReadBit bit(double r) const {
    return r >= mid + band ? ReadBit::kOne : r <= mid - band ? ReadBit::kZero : ReadBit::kUnknown;
  }
};

// One value per sample of a track's history (same indices).
using TrackBits = std::array<ReadBit, kTrackHistory>;

// Reads samples [from, history.size()) of `history` into bits[from..); the others
// are left as they are. Constant modulation reads every measured sample as 1.
void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits);

// One track's bits kept current from frame to frame, re-reading only what can
// have changed. A sample's bit depends only on the samples within 2 x window of
// it (its level window, then the clear 1s around it), so once 2 x window newer
// samples follow it, it is final, unless dropping the oldest samples takes
// some of its context away, which only the oldest 2 x window can lose. An update
// re-reads the newest 2 x window + 1 samples and the new ones (their levels
// only where the window reaches a new sample), and keeps the rest, moved along
// with the history.
class TrackBitReader {
 public:
  // Afterwards bits()[from, history.size()) are what read_track_bits(history,
  // modulation, reading, from, ...) reads there. Every call must pass the same
  // track's history (at most kTrackHistory new samples since the previous
  // call) and the same modulation and reading.
  void update(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
              const BitReading& reading, size_t from);

  // One value per sample of the history last passed to update() (same indices).
  const TrackBits& bits() const { return bits_; }

 private:
  TrackBits bits_{};
  TrackBits pass1_{};  // each sample read against its window's brightest sample
  std::array<double, kTrackHistory> bright_{};  // that sample's intensity; 0: none to read against
  std::array<BitSplit, kTrackHistory> split_{};   // the window's levels: ratios to bright_ read as 1 or 0
  size_t size_ = 0;           // history size at the last update; 0: nothing read yet
  int64_t newest_frame_ = 0;  // the frame of its newest sample
  size_t current_from_ = 0;   // bits_[current_from_, size_) were current then
  size_t pass1_from_ = 0;     // and pass1_, bright_ over [pass1_from_, size_)
};

}  // namespace tetrapulse
