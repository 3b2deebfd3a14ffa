#include "background_histogram.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tetrapulse::blob_internal {
namespace {

constexpr int kMaxBins = 4096;
constexpr int kRowStepArea = 1 << 16;  // 8-bit windows this large count every other row
constexpr int kPartials = 8;           // partial 8-bit counts of such windows (4 for smaller ones)

int bit_length(unsigned v) {
  int n = 0;
  while (v) {
    ++n;
    v >>= 1;
  }
  return n;
}

// The band count needs SSE2 and 64-bit lane extraction (x86-64).
#if defined(__SSE2__) && defined(__x86_64__)
#define TETRAPULSE_BAND_COUNT 1
#endif

#if defined(TETRAPULSE_BAND_COUNT)
// A whole image's background, flattened, lies in a few grey levels (99.5 % of the
// pipeline benchmark's pixels in 8 consecutive ones), and counting it one increment
// at a time was a fifth of a full frame. Pixels within a band of 8 levels are counted
// 16 at a time into per-lane byte counters (a compare and a subtract per level); the
// rest, markers mostly, one by one into the partial histograms. Exact either way: the
// band only decides which pixels take the fast path.
class BandCounter {
 public:
  // Takes the 8 consecutive levels holding the most of the partial histograms' pixels
  // so far (the first counted row), when they hold at least 7/8 of the `counted`.
  void choose(const uint32_t* h, int parts, int counted) {
    uint32_t c[256];
    for (int b = 0; b < 256; ++b) {
      c[b] = 0;
      for (int k = 0; k < parts; ++k) c[b] += h[256 * k + b];
    }
    uint32_t in = 0, best = 0;
    int base = 0;
    for (int b = 0; b < 256; ++b) {
      in += c[b] - (b >= kLevels ? c[b - kLevels] : 0);
      if (b >= kLevels - 1 && in > best) best = in, base = b - (kLevels - 1);
    }
    on_ = counted > 0 && uint64_t(best) * 8 >= uint64_t(counted) * 7;
    base_level_ = base;
    base_ = _mm_set1_epi8(char(base));
    for (int k = 0; k < kLevels; ++k) totals_[k] = 0;
  }
  bool on() const { return on_; }

  // Counts p[0, x) for the largest x <= width that is a multiple of 16; returns x.
  int count_row(const uint8_t* p, int width, uint32_t* h) {
    const __m128i zero = _mm_setzero_si128();
    // Counters and levels as locals, the loops over them unrolled (members indexed in a
    // loop stayed in memory).
    __m128i a[kLevels], level[kLevels];
#pragma GCC unroll 8
    for (int k = 0; k < kLevels; ++k) a[k] = zero, level[k] = _mm_set1_epi8(char(k));
    int x = 0;
    // At most 255 vectors between emptyings (a byte counter holds 255). The vectors
    // with lanes outside the band (d > 7 as unsigned bytes) are listed and those
    // lanes counted after the chunk, so that the vector loop has no branch on data.
    int listed[255];
    while (x + 16 <= width) {
      const int end = std::min(width - 15, x + 255 * 16);
      int n = 0;
      for (; x < end; x += 16) {
        const __m128i d = offsets(p + x);
#pragma GCC unroll 8
        for (int k = 0; k < kLevels; ++k) a[k] = _mm_sub_epi8(a[k], _mm_cmpeq_epi8(d, level[k]));
        listed[n] = x;
        n += outside(d) != 0;
      }
#pragma GCC unroll 8
      for (int k = 0; k < kLevels; ++k) {
        const __m128i s = _mm_sad_epu8(a[k], zero);  // the two halves' byte sums
        totals_[k] += uint64_t(_mm_cvtsi128_si64(s)) + uint64_t(_mm_cvtsi128_si64(_mm_unpackhi_epi64(s, s)));
        a[k] = zero;
      }
      // The listed vectors' lanes outside the band, one by one; four partial
      // histograms by lane, as a saturated marker repeats one value.
      for (int j = 0; j < n; ++j) {
        const uint8_t* v = p + listed[j];
        for (unsigned out = outside(offsets(v)); out != 0;) {
          const int i = __builtin_ctz(out);
          ++h[256 * (i & 3) + v[i]];
          out &= out - 1;
        }
      }
    }
    return x;
  }

  // Adds the band's counts to partial histogram 0.
  void add_to(uint32_t* h) const {
    if (!on_) return;
    for (int k = 0; k < kLevels; ++k) h[base_level_ + k] += uint32_t(totals_[k]);
  }

 private:
  static constexpr int kLevels = 8;

  // 16 pixels' levels above the band's first (a pixel in the band: 0..7).
  __m128i offsets(const uint8_t* v) const {
    return _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(v)), base_);
  }
  // The lanes whose offset lies outside the band (above 7 as an unsigned byte), as bits.
  static unsigned outside(__m128i d) {
    const __m128i in = _mm_cmpeq_epi8(_mm_subs_epu8(d, _mm_set1_epi8(kLevels - 1)), _mm_setzero_si128());
    return ~unsigned(_mm_movemask_epi8(in)) & 0xFFFFu;
  }

  bool on_ = false;
  int base_level_ = 0;
  __m128i base_ = _mm_setzero_si128();
  uint64_t totals_[kLevels] = {};
};
#endif

}  // namespace

void BackgroundHistogram::count(const cv::Mat& image, cv::Rect window) {
  total_ = static_cast<uint32_t>(std::max(0, window.area()));
  if (image.depth() == CV_8U) {
    shift_ = 0;
    quantum_ = 1;
    used_ = 256;
    bins_.resize(256);
    // Background pixels fill a few bins: counted into one histogram, each count
    // waits for the previous one to the same bin. Four interleaved histograms
    // pay for their clearing already in a 27 x 27 ROI window. They are all zero
    // between calls: the sum below clears them as it reads them.
    partial_.resize(kPartials * 256, 0);
    uint32_t* h = partial_.data();
    // A whole image's statistics need no more than every other row (180 000
    // pixels of 752 x 480): its count was a fifth of a full-frame search.
    const bool large = window.area() >= kRowStepArea;
    const int step = large ? 2 : 1;
    total_ = static_cast<uint32_t>(((window.height + step - 1) / step) * std::max(0, window.width));
    // A large window's flat background puts most pixels in a few bins: with four
    // partial counts each increment still waited on the one four pixels before (a
    // fifth of a full frame's wall clock); eight leave twice the room.
    const int parts = large ? kPartials : 4;
#if defined(TETRAPULSE_BAND_COUNT)
    BandCounter band;
#endif
    for (int y = window.y; y < window.y + window.height; y += step) {
      const uint8_t* p = image.ptr<uint8_t>(y) + window.x;
      int x = 0;
#if defined(TETRAPULSE_BAND_COUNT)
      if (band.on()) x = band.count_row(p, window.width, h);
#endif
      if (large) {
        for (; x + 8 <= window.width; x += 8) {
          ++h[p[x]];
          ++h[256 + p[x + 1]];
          ++h[512 + p[x + 2]];
          ++h[768 + p[x + 3]];
          ++h[1024 + p[x + 4]];
          ++h[1280 + p[x + 5]];
          ++h[1536 + p[x + 6]];
          ++h[1792 + p[x + 7]];
        }
      }
      for (; x + 4 <= window.width; x += 4) {
        ++h[p[x]];
        ++h[256 + p[x + 1]];
        ++h[512 + p[x + 2]];
        ++h[768 + p[x + 3]];
      }
      for (; x < window.width; ++x) ++h[p[x]];
#if defined(TETRAPULSE_BAND_COUNT)
      if (large && y == window.y) band.choose(h, parts, window.width);
#endif
    }
#if defined(TETRAPULSE_BAND_COUNT)
    band.add_to(h);
#endif
    uint32_t* bins = bins_.data();
    int b = 0, first = 256, last = -1;  // occupied bins lie in [first, last + 3]
#if defined(__SSE2__)
    // Four bins at a time: the sum was a third of a ROI window's count.
    const auto at = [](uint32_t* p) { return reinterpret_cast<__m128i*>(p); };
    for (; b < 256; b += 4) {
      __m128i sum = _mm_add_epi32(_mm_add_epi32(_mm_loadu_si128(at(h + b)), _mm_loadu_si128(at(h + 256 + b))),
                                  _mm_add_epi32(_mm_loadu_si128(at(h + 512 + b)), _mm_loadu_si128(at(h + 768 + b))));
      for (int k = 4; k < parts; ++k) sum = _mm_add_epi32(sum, _mm_loadu_si128(at(h + 256 * k + b)));
      _mm_storeu_si128(at(bins + b), sum);
      for (int k = 0; k < parts; ++k) _mm_storeu_si128(at(h + 256 * k + b), _mm_setzero_si128());
      if (_mm_movemask_epi8(_mm_cmpeq_epi32(sum, _mm_setzero_si128())) != 0xFFFF) {
        first = std::min(first, b);
        last = b;
      }
    }
#endif
    for (; b < 256; ++b) {
      bins[b] = 0;
      for (int k = 0; k < parts; ++k) bins[b] += h[256 * k + b], h[256 * k + b] = 0;
      if (bins[b] != 0) first = std::min(first, b), last = b;
    }
    find_occupied(first, std::min(last + 3, 255));
    return;
  }
  // 16-bit: bins as wide as the data's quantum (a 10- or 12-bit sensor shifted
  // up fills every 64th or 16th value), and wide enough for at most 4096 bins.
  // Large windows count every value once, then fold; small ones look at their
  // values twice rather than clear 65536 counters.
  unsigned top = 0, any_bits = 0;
  const bool full = window.area() >= 65536;
  if (full) {
    full_.assign(65536, 0);
    for (int y = window.y; y < window.y + window.height; ++y) {
      const uint16_t* p = image.ptr<uint16_t>(y) + window.x;
      for (int x = 0; x < window.width; ++x) ++full_[p[x]];
    }
    for (unsigned v = 0; v < 65536; ++v) {
      if (full_[v] == 0) continue;
      top = v;
      any_bits |= v;
    }
  } else {
    for (int y = window.y; y < window.y + window.height; ++y) {
      const uint16_t* p = image.ptr<uint16_t>(y) + window.x;
      for (int x = 0; x < window.width; ++x) {
        top = std::max<unsigned>(top, p[x]);
        any_bits |= p[x];
      }
    }
  }
  int quantum_shift = 0;
  while (any_bits != 0 && (any_bits & 1u) == 0) {
    ++quantum_shift;
    any_bits >>= 1;
  }
  shift_ = std::max(quantum_shift, bit_length(top) - 12);
  quantum_ = 1 << quantum_shift;
  used_ = static_cast<int>(top >> shift_) + 1;
  bins_.assign(static_cast<size_t>(std::min(used_, kMaxBins)), 0);
  if (full) {
    for (unsigned v = 0; v <= top; ++v) bins_[v >> shift_] += full_[v];
  } else {
    for (int y = window.y; y < window.y + window.height; ++y) {
      const uint16_t* p = image.ptr<uint16_t>(y) + window.x;
      for (int x = 0; x < window.width; ++x) ++bins_[p[x] >> shift_];
    }
  }
  find_occupied(0, int(bins_.size()) - 1);
}

void BackgroundHistogram::find_occupied(int from, int to) {
  lo_ = from;
  hi_ = to;
  while (lo_ <= hi_ && bins_[size_t(lo_)] == 0) ++lo_;
  while (hi_ >= lo_ && bins_[size_t(hi_)] == 0) --hi_;
}

BackgroundFit BackgroundHistogram::fit_background(double saturation) const {
  BackgroundFit fit;
  if (total_ == 0) return fit;
  const int n = used_;
  int top = std::max(hi_, 0);
  int below = top - 1;
  while (below >= 0 && bins_[below] == 0) --below;
  const bool clipped_top = below >= 0 && (bin_centre(top) >= saturation - 0.5 * bin_width() ||
                                          (bins_[top] >= 4 && bins_[top] >= 4 * bins_[below]));
  const int mode_end = clipped_top ? below + 1 : n;
  // The mode and its width are read where bins hold enough pixels to have a peak:
  // deep data in a small window spreads its noise over more values than it has
  // pixels for (16 bits, sigma 58, a 26 x 26 ROI: a pixel or two per value), and
  // the tallest single bin is a spike of noise whose width is one bin (sigma 0.55
  // for 58, and noise taken for a marker). Neighbouring bins are merged, 2, 4, 8...
  // at a time, until the tallest merged bin holds max(8, 1/32 of the pixels).
  const uint32_t enough = std::max<uint32_t>(8, total_ / 32);
  // The first tallest of bins [from, to).
  const auto mode_of = [](const uint32_t* h, int from, int to) {
    int mode = from;
    for (int b = from + 1; b < to; ++b)
      if (h[b] > h[mode]) mode = b;
    return mode;
  };
  const uint32_t* h = bins_.data();
  int coarse = mode_end, merge = 1;
  // Bins outside [lo_, hi_] are empty: the first tallest lies within (a window's
  // values span a few dozen of its 256 bins).
  const int from = std::max(0, std::min(lo_, coarse - 1)), to = std::min(hi_ + 1, coarse);
  int mode = from < to ? mode_of(h, from, to) : mode_of(h, 0, coarse);
  if (h[mode] < enough) merged_.assign(bins_.begin(), bins_.begin() + mode_end);
  while (h[mode] < enough && merge < mode_end) {
    // Pairs of the previous level, in place.
    merge *= 2;
    const int finer = coarse;
    coarse = (finer + 1) / 2;
    for (int b = 0; b < coarse; ++b)
      merged_[size_t(b)] = merged_[size_t(2 * b)] + (2 * b + 1 < finer ? merged_[size_t(2 * b + 1)] : 0);
    h = merged_.data();
    mode = mode_of(h, 0, coarse);
  }
  // Initial sigma from the full width at half maximum.
  const double half = h[mode] * 0.5;
  int lo = mode, hi = mode;
  while (lo > 0 && h[lo - 1] >= half) --lo;
  while (hi + 1 < coarse && h[hi + 1] >= half) ++hi;
  double mean = (mode + 0.5) * merge - 0.5;
  double sigma = std::max((hi - lo + 1) * merge / 2.3548, 0.5);
  // 3-sigma clipping. A normal truncated at +-3 sigma keeps 0.97334 of its
  // variance; binning adds 1/12 bin^2 (Sheppard).
  for (int iter = 0; iter < 20; ++iter) {
    const int a = std::max(0, static_cast<int>(std::floor(mean - 3 * sigma)));
    const int b = std::min(n - 1, static_cast<int>(std::ceil(mean + 3 * sigma)));
    double s0 = 0, s1 = 0, s2 = 0;
    for (int k = a; k <= b; ++k) {
      const double c = bins_[k];
      s0 += c;
      s1 += c * k;
      s2 += c * double(k) * k;
    }
    if (s0 <= 0) break;
    const double m = s1 / s0;
    const double var = std::max(0.0, s2 / s0 - m * m - 1.0 / 12.0) / 0.97334;
    const double sd = std::sqrt(var);
    const bool settled = std::abs(m - mean) < 1e-3 && std::abs(std::max(sd, 0.5) - sigma) < 1e-3;
    mean = m;
    sigma = std::max(sd, 0.5);  // keep the clipping window at least +-1.5 bins wide
    fit.sigma = sd;
    if (settled) break;
  }
  fit.mean = bin_centre(mean);
  fit.sigma *= bin_width();
  return fit;
}

double BackgroundHistogram::otsu() const {
  if (lo_ > hi_) return -1;
  const int lo = lo_, hi = hi_;
  // An empty bin leaves the split as it was: only the others are visited. They
  // are listed first without a branch each (marker pixels leave empty bins
  // between full ones at random, and each such branch would be a coin toss).
  std::array<uint16_t, kMaxBins> full;
  int count = 0;
  for (int b = lo; b <= hi; ++b) {
    full[size_t(count)] = uint16_t(b);
    count += bins_[b] != 0;
  }
  double sum_all = 0;
  for (int k = 0; k < count; ++k) sum_all += double(bins_[full[size_t(k)]]) * full[size_t(k)];
  double w0 = 0, sum0 = 0, best = -1;
  int best_t = -1;
  for (int k = 0; k < count && full[size_t(k)] < hi; ++k) {
    const int t = full[size_t(k)];
    w0 += bins_[t];
    sum0 += double(bins_[t]) * t;
    const double w1 = double(total_) - w0;
    if (w0 <= 0) continue;
    if (w1 <= 0) break;
    const double d = sum0 / w0 - (sum_all - sum0) / w1;
    const double between = w0 * w1 * d * d;
    if (between > best) {
      best = between;
      best_t = t;
    }
  }
  if (best_t < 0) return -1;
  // Bins 0..best_t are the darker class; the brighter starts at (best_t + 1) << shift.
  return double((best_t + 1) << shift_) - 0.5;
}

}  // namespace tetrapulse::blob_internal
