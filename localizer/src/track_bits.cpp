#include "tetrapulse/localizer/track_bits.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include <opencv2/core.hpp>

namespace tetrapulse {
namespace {

// What reading needs of each sample, in history order (no ring indexing in the
// inner loops).
struct SampleLevels {
  std::array<double, kTrackHistory> intensity{};
  std::array<bool, kTrackHistory> detected{};
  std::array<bool, kTrackHistory> measured{};
  std::array<bool, kTrackHistory> saturated{};
  size_t n = 0;

  explicit SampleLevels(const RingBuffer<TrackSample, kTrackHistory>& history) : n(history.size()) {
    for (size_t j = 0; j < n; ++j) {
      const TrackSample& s = history[j];
      intensity[j] = s.intensity;
      detected[j] = s.detected;
      measured[j] = s.measured;
      saturated[j] = s.saturated;
    }
  }
};

using Split = BitSplit;

struct Thresholds {
  Split nominal;  // the modulation's own levels
  size_t w = 1;

  Thresholds(const Modulation& modulation, const BitReading& reading) {
    const double low = modulation.kind == ModulationKind::kTwoLevel ? modulation.low : 0.0;
    nominal.mid = (1 + low) / 2;
    nominal.band = reading.band_fraction * (1 - low);
    w = size_t(std::max(reading.window, 1));
  }
};

// Two levels of a window whose light does not show the nominal contrast: a
// saturated marker, whose clipped 1 is far less than 1/low times its 0, or a
// camera whose response is not linear (gamma-encoded video). Only the order of
// intensities survives such a response, so the levels are learned from the
// window's detected samples themselves, on y = log(intensity) with a common
// smooth drift (the marker closing in or turning away):
//   y_k = a + b x_k + q x_k^2 + c bit_k,   x_k = k - centre,
// fitted by least squares, alternating with the bits: the widest gap between
// the sorted detrended values y_k - b x_k - q x_k^2 splits 0s from 1s. The split
// holds when that gap is
// - at least log kMinContrast (a saturated 1 still gains a ring of pixels over its 0),
// - at least twice the spread of the values on either side (a drift the line
//   does not follow spreads values evenly; a code splits them into two tight groups),
// - with two samples or more on each side (one odd sample is no level).
struct LearnedLevels {
  double one = 0;    // detrended log level of the 1s
  double slope = 0;      // b, per sample
  double curvature = 0;  // q, per sample^2
  double centre = 0;
  BitSplit split;    // ratios to the 1 level: the gap's middle, its band the middle half of the gap
  double zero = 0;   // the brightest 0 as a ratio to the 1 level

  double bright(size_t k) const {
    const double x = double(k) - centre;
    return std::exp(one + slope * x + curvature * x * x);
  }
};

constexpr double kMinContrast = 1.04;

// The widest gap of d[0..n) sorted into `sorted` (two or more values each side):
// its index i (between sorted[i] and sorted[i + 1]); false when there is none.
bool widest_gap(const std::array<double, kTrackHistory>& d, size_t n, std::array<double, kTrackHistory>* sorted,
                size_t* gap) {
  std::copy(d.begin(), d.begin() + std::ptrdiff_t(n), sorted->begin());
  std::sort(sorted->begin(), sorted->begin() + std::ptrdiff_t(n));
  double widest = -1;
  for (size_t i = 1; i + 2 < n; ++i)
    if ((*sorted)[i + 1] - (*sorted)[i] > widest) widest = (*sorted)[i + 1] - (*sorted)[i], *gap = i;
  return widest >= 0;
}

// Least squares of y = a + b x + q x^2 (+ c bit, when `one` is given): the
// drift's (b, q).
bool fit_drift(const std::array<double, kTrackHistory>& x, const std::array<double, kTrackHistory>& y,
               const std::array<bool, kTrackHistory>* one, size_t n, double* b, double* q) {
  cv::Matx44d A = cv::Matx44d::zeros();
  cv::Vec4d r = cv::Vec4d::all(0), coef;
  const int k = one ? 4 : 3;
  for (size_t i = 0; i < n; ++i) {
    const double f[4] = {1, x[i], x[i] * x[i], one && (*one)[i] ? 1.0 : 0.0};
    for (int u = 0; u < k; ++u) {
      r[u] += f[u] * y[i];
      for (int v = 0; v < k; ++v) A(u, v) += f[u] * f[v];
    }
  }
  if (k == 3) A(3, 3) = 1;
  if (!cv::solve(A, r, coef, cv::DECOMP_LU)) return false;
  *b = coef[1];
  *q = coef[2];
  return true;
}

bool learn_levels(const SampleLevels& h, size_t begin, size_t end, LearnedLevels* out) {
  std::array<double, kTrackHistory> x{}, y{}, d{}, sorted{};
  std::array<bool, kTrackHistory> one{};
  size_t n = 0;
  const double centre = 0.5 * double(begin + end - 1);
  for (size_t k = begin; k < end; ++k)
    if (h.measured[k] && h.detected[k] && h.intensity[k] > 0) x[n] = double(k) - centre, y[n++] = std::log(h.intensity[k]);
  if (n < 4) return false;
  // The drift first, from a parabola through all of them (the code's steps,
  // spread over the window, hardly bend it); then the bits and the drift in
  // turn. A parabola, not a line: light grows as 1 / distance^2, and a marker
  // closing in at constant speed brightens ever faster.
  double b = 0, q = 0, threshold = 0;
  if (n < 6 || !fit_drift(x, y, nullptr, n, &b, &q)) q = 0;
  size_t gap = 0;
  for (int pass = 0; pass < 4; ++pass) {
    for (size_t i = 0; i < n; ++i) d[i] = y[i] - b * x[i] - q * x[i] * x[i];
    if (!widest_gap(d, n, &sorted, &gap)) return false;
    threshold = 0.5 * (sorted[gap] + sorted[gap + 1]);
    bool changed = pass == 0;
    for (size_t i = 0; i < n; ++i) {
      const bool is_one = d[i] > threshold;
      changed = changed || is_one != one[i];
      one[i] = is_one;
    }
    if (!changed) break;
    if (!fit_drift(x, y, &one, n, &b, &q)) return false;
    if (n < 6) q = 0;
  }
  const double low = sorted[gap], high = sorted[gap + 1], widest = high - low;
  const double spread = std::max(low - sorted[0], sorted[n - 1] - high);
  if (!(widest >= std::log(kMinContrast)) || !(widest >= 2 * spread)) return false;
  double ones = 0;
  int count = 0;
  for (size_t i = 0; i < n; ++i)
    if (d[i] > threshold) ones += d[i], ++count;
  out->one = ones / count;
  out->slope = b;
  out->curvature = q;
  out->centre = centre;
  const double lo = std::exp(low + widest / 4 - out->one), hi = std::exp(high - widest / 4 - out->one);
  out->split.mid = 0.5 * (lo + hi);
  out->split.band = 0.5 * (hi - lo);
  out->zero = std::exp(low - out->one);
  return true;
}

// Whether the nominal levels leave some of a window's detected samples unknown
// against its brightest.
bool nominal_doubts(const SampleLevels& h, size_t begin, size_t end, double top, const BitSplit& nominal) {
  int detected = 0, unknown = 0;
  for (size_t k = begin; k < end; ++k) {
    if (!h.measured[k] || !h.detected[k]) continue;
    ++detected;
    unknown += nominal.bit(h.intensity[k] / top) == ReadBit::kUnknown;
  }
  return unknown > 0 && detected > 0;
}

// Pass 1 over samples [first, last): each read against the brightest detected
// sample within its window (bright[j], 0 when there is none to read against).
void read_against_window(const SampleLevels& h, const Modulation& modulation, const Thresholds& t, size_t first,
                         size_t last, TrackBits* pass1, std::array<double, kTrackHistory>* bright,
                         std::array<Split, kTrackHistory>* split) {
  const size_t n = h.n, w = t.w;
  size_t window_end = 0;  // the window whose levels these are (its end): the newest w + 1 samples share one
  double top = 0, dim = 0;
  bool any_detected = false, any_saturated = false;
  bool readable = false, learned = false;
  LearnedLevels levels;
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
      any_detected = any_saturated = false;
      bool any = false;
      for (size_t k = lo_begin; k < hi_end; ++k) {
        if (!h.measured[k]) continue;
        const double v = h.intensity[k];
        if (h.detected[k] && (!any_detected || v > top)) top = v, any_detected = true;
        any_saturated = any_saturated || (h.detected[k] && h.saturated[k]);
        dim = any ? std::min(dim, v) : v;
        any = true;
      }
      // Two levels: both must have been seen (the dimmest sample reads as a 0), or
      // a run of 1s would read as 0s and a run of 0s as 1s; a saturated window's
      // levels are learned from its samples. An on-off 0 is dark, a level known
      // without seeing it.
      readable = any_detected && top > 0;
      learned = false;
      if (readable && modulation.kind == ModulationKind::kTwoLevel) {
        // The nominal levels hold unless the light is clipped, shows no 0 they
        // can read, or leaves samples unknown; then the levels the light shows,
        // when the nominal ones could not read their 0s.
        const bool nominal = dim <= top * (t.nominal.mid - t.nominal.band);
        const bool doubt = any_saturated || !nominal || nominal_doubts(h, lo_begin, hi_end, top, t.nominal);
        learned = doubt && learn_levels(h, lo_begin, hi_end, &levels) &&
                  (any_saturated || !nominal || levels.zero > t.nominal.mid - t.nominal.band);
        readable = learned || nominal;
      }
    }
    if (!readable) continue;
    (*bright)[j] = learned ? levels.bright(j) : top;
    (*split)[j] = learned ? levels.split : t.nominal;
    (*pass1)[j] = (*split)[j].bit(h.intensity[j] / (*bright)[j]);
  }
}

// Pass 2 over samples [from, to): each read against the bright level
// interpolated between the nearest clear 1s of pass 1 before and after it
// (within the window), so that a marker whose light grows or fades within the
// window is still read. Needs pass 1 within w of [from, to).
void read_against_neighbours(const SampleLevels& h, const Modulation& modulation, const Thresholds& t,
                             const TrackBits& pass1, const std::array<double, kTrackHistory>& bright,
                             const std::array<Split, kTrackHistory>& split, size_t from, size_t to, TrackBits* bits) {
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
    out = split[j].bit(h.intensity[j] / level);
  }
}

}  // namespace

void read_track_bits(const RingBuffer<TrackSample, kTrackHistory>& history, const Modulation& modulation,
                     const BitReading& reading, size_t from, TrackBits* bits) {
  const SampleLevels h(history);
  const Thresholds t(modulation, reading);
  TrackBits pass1{};
  std::array<double, kTrackHistory> bright{};
  std::array<Split, kTrackHistory> split{};
  read_against_window(h, modulation, t, from > t.w ? from - t.w : 0, h.n, &pass1, &bright, &split);
  read_against_neighbours(h, modulation, t, pass1, bright, split, from, h.n, bits);
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
    std::memmove(split_.data(), split_.data() + dropped, kept * sizeof(split_[0]));
  }
  // Pass 1 changes where the window now reaches new samples, and (after a drop)
  // where the oldest sample cut it: the first w samples.
  const size_t end_from = anew ? 0 : kept > w ? kept - w : 0;
  size_t level_from = anew ? n : std::max(pass1_from_ > dropped ? pass1_from_ - dropped : 0, dropped > 0 ? w : 0);
  read_against_window(h, modulation, t, end_from, n, &pass1_, &bright_, &split_);
  level_from = std::min(level_from, end_from);
  // Pass 2 needs pass 1 within w of the samples it reads.
  const auto read_bits = [&](size_t first, size_t last) {
    if (first >= last) return;
    const size_t needed = first > w ? first - w : 0;
    if (needed < level_from) read_against_window(h, modulation, t, needed, level_from, &pass1_, &bright_, &split_);
    level_from = std::min(level_from, needed);
    read_against_neighbours(h, modulation, t, pass1_, bright_, split_, first, last, &bits_);
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
