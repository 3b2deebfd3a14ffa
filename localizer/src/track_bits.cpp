#include "tetrapulse/localizer/track_bits.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace tetrapulse {
namespace {

// What reading needs of each sample, in history order (no ring indexing in the
// inner loops).
struct SampleLevels {
  std::array<double, kTrackHistory> intensity{};
  std::array<bool, kTrackHistory> detected{};
  std::array<bool, kTrackHistory> measured{};
  size_t n = 0;

  explicit SampleLevels(const RingBuffer<TrackSample, kTrackHistory>& history) : n(history.size()) {
    for (size_t j = 0; j < n; ++j) {
      const TrackSample& s = history[j];
      intensity[j] = s.intensity;
      detected[j] = s.detected;
      measured[j] = s.measured;
    }
  }
};

struct Thresholds {
  double mid = 0, band = 0;
  size_t w = 1;

  Thresholds(const Modulation& modulation, const BitReading& reading) {
    const double low = modulation.kind == ModulationKind::kTwoLevel ? modulation.low : 0.0;
    mid = (1 + low) / 2;
    band = reading.band_fraction * (1 - low);
    w = size_t(std::max(reading.window, 1));
  }
  ReadBit bit(double r) const {
    return r >= mid + band ? ReadBit::kOne : r <= mid - band ? ReadBit::kZero : ReadBit::kUnknown;
  }
};

// Pass 1 over samples [first, last): each read against the brightest detected
// sample within its window (bright[j], 0 when there is none to read against).
void read_against_window(const SampleLevels& h, const Modulation& modulation, const Thresholds& t, size_t first,
                         size_t last, TrackBits* pass1, std::array<double, kTrackHistory>* bright) {
  const size_t n = h.n, w = t.w;
  size_t window_end = 0;  // the window whose levels these are (its end): the newest w + 1 samples share one
  double top = 0, dim = 0;
  bool any_detected = false;
  for (size_t j = first; j < last; ++j) {
    (*pass1)[j] = ReadBit::kUnknown;
    (*bright)[j] = 0;
    if (!h.measured[j]) continue;
    if (modulation.kind == ModulationKind::kConstant) {
      (*pass1)[j] = ReadBit::kOne;
      continue;
    }
    // The window around j; near the newest sample it extends further back, so
    // that it always spans 2w + 1 samples.
    const size_t hi_end = std::min(n, j + w + 1);
    const size_t lo_begin = hi_end >= 2 * w + 1 ? hi_end - (2 * w + 1) : 0;
    if (hi_end != window_end) {
      window_end = hi_end;
      top = dim = 0;
      any_detected = false;
      bool any = false;
      for (size_t k = lo_begin; k < hi_end; ++k) {
        if (!h.measured[k]) continue;
        const double v = h.intensity[k];
        if (h.detected[k] && (!any_detected || v > top)) top = v, any_detected = true;
        dim = any ? std::min(dim, v) : v;
        any = true;
      }
    }
    if (!any_detected || !(top > 0)) continue;
    // Two levels: both must have been seen (the dimmest sample reads as a 0), or
    // a run of 1s would read as 0s and a run of 0s as 1s. An on-off 0 is dark,
    // a level known without seeing it.
    if (modulation.kind == ModulationKind::kTwoLevel && !(dim <= top * (t.mid - t.band))) continue;
    (*bright)[j] = top;
    (*pass1)[j] = t.bit(h.intensity[j] / top);
  }
}

// Pass 2 over samples [from, to): each read against the bright level
// interpolated between the nearest clear 1s of pass 1 before and after it
// (within the window), so that a marker whose light grows or fades within the
// window is still read. Needs pass 1 within w of [from, to).
void read_against_neighbours(const SampleLevels& h, const Modulation& modulation, const Thresholds& t,
                             const TrackBits& pass1, const std::array<double, kTrackHistory>& bright, size_t from,
                             size_t to, TrackBits* bits) {
  const size_t n = h.n, w = t.w;
  for (size_t j = from; j < to; ++j) {
    ReadBit& out = (*bits)[j];
    out = pass1[j];
    if (modulation.kind == ModulationKind::kConstant || !(bright[j] > 0)) continue;
    int before = -1, after = -1;
    for (size_t k = j + 1; k-- > (j >= w ? j - w : 0);)
      if (pass1[k] == ReadBit::kOne && h.detected[k]) {
        before = int(k);
        break;
      }
    for (size_t k = j; k < std::min(n, j + w + 1); ++k)
      if (pass1[k] == ReadBit::kOne && h.detected[k]) {
        after = int(k);
        break;
      }
    double level = bright[j];
    if (before >= 0 && after >= 0 && after != before) {
      const double a = h.intensity[size_t(before)], b = h.intensity[size_t(after)];
      level = a + (b - a) * double(int(j) - before) / double(after - before);
    } else if (before >= 0 || after >= 0) {
      level = h.intensity[size_t(before >= 0 ? before : after)];
    }
    if (!(level > 0)) continue;
    out = t.bit(h.intensity[j] / level);
  }
}

}  // namespace

void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits) {
  const SampleLevels h(history);
  const Thresholds t(modulation, reading);
  TrackBits pass1{};
  std::array<double, kTrackHistory> bright{};
  read_against_window(h, modulation, t, from > t.w ? from - t.w : 0, h.n, &pass1, &bright);
  read_against_neighbours(h, modulation, t, pass1, bright, from, h.n, bits);
}

void TrackBitReader::update(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                            const BitReading& reading, size_t from) {
  const SampleLevels h(history);
  const Thresholds t(modulation, reading);
  const size_t n = h.n, w = t.w;
  // Where the newest sample of the last update is now: samples carry increasing frames.
  size_t kept = 0;  // samples of the last update still in the history
  for (size_t j = n; j-- > 0 && size_ > 0 && history[j].frame >= newest_frame_;)
    if (history[j].frame == newest_frame_) kept = j + 1;
  const bool anew = kept == 0 || kept > size_;  // a new track, or more new samples than the history holds
  const size_t dropped = anew ? 0 : size_ - kept;
  if (dropped > 0) {
    // Move what was read along with the history.
    std::memmove(bits_.data(), bits_.data() + dropped, kept * sizeof(ReadBit));
    std::memmove(pass1_.data(), pass1_.data() + dropped, kept * sizeof(ReadBit));
    std::memmove(bright_.data(), bright_.data() + dropped, kept * sizeof(double));
  }
  // Pass 1 changes where the window now reaches new samples, and (after a drop)
  // where the oldest sample cut it: the first w samples.
  const size_t end_from = anew ? 0 : kept > w ? kept - w : 0;
  size_t level_from = anew ? n : std::max(pass1_from_ > dropped ? pass1_from_ - dropped : 0, dropped > 0 ? w : 0);
  read_against_window(h, modulation, t, end_from, n, &pass1_, &bright_);
  level_from = std::min(level_from, end_from);
  // Pass 2 needs pass 1 within w of the samples it reads.
  const auto read_bits = [&](size_t first, size_t last) {
    if (first >= last) return;
    const size_t needed = first > w ? first - w : 0;
    if (needed < level_from) read_against_window(h, modulation, t, needed, level_from, &pass1_, &bright_);
    level_from = std::min(level_from, needed);
    read_against_neighbours(h, modulation, t, pass1_, bright_, first, last, &bits_);
  };
  // Bits change within 2w of either change of pass 1; and bits asked for that
  // were not read before are read.
  const size_t current = anew ? n : current_from_ > dropped ? current_from_ - dropped : 0;
  const size_t tail = anew ? from : std::max(from, kept > 2 * w ? kept - 2 * w : 0);
  const size_t head_end = std::min(tail, std::max(current, dropped > 0 ? 2 * w : 0));
  read_bits(from, head_end);
  read_bits(tail, n);
  size_ = n;
  newest_frame_ = n > 0 ? history[n - 1].frame : 0;
  current_from_ = std::min(from, n);
  pass1_from_ = std::min(level_from, n);
}

}  // namespace tetrapulse
