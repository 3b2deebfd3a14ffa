#include "background_flattening.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tetrapulse::blob_internal {
namespace {

// The value of rank `k` among `n` 8-bit values counted in `count` (as a sort gives).
int rank_in_counts(const uint32_t count[256], size_t k) {
  size_t below = 0;
  int v = 0;
  while (below + count[v] <= k) below += count[v++];
  return v;
}

// The 30th percentile of a cell's pixels at every step-th row and column.
template <typename T>
float low_of_cell(const cv::Mat& work, int x0, int y0, int cell, int step, std::vector<int>* values) {
  const int x1 = std::min(x0 + cell, work.cols), y1 = std::min(y0 + cell, work.rows);
  const size_t n = size_t((x1 - x0 + step - 1) / step) * size_t((y1 - y0 + step - 1) / step);
  if constexpr (sizeof(T) == 1) {
    // Counting beats selection from a quarter as many values as bins: the
    // 64-pixel cells cut by the image's edge (128-192 values), selected, took
    // a twentieth of a full frame.
    if (n >= 64) {
      uint32_t count[256] = {};
      for (int y = y0; y < y1; y += step) {
        const T* row = work.ptr<T>(y);
        for (int x = x0; x < x1; x += step) ++count[row[x]];
      }
      return float(rank_in_counts(count, n * 3 / 10));
    }
  }
  values->clear();
  for (int y = y0; y < y1; y += step) {
    const T* row = work.ptr<T>(y);
    for (int x = x0; x < x1; x += step) values->push_back(row[x]);
  }
  auto low = values->begin() + std::ptrdiff_t(values->size() * 3 / 10);
  std::nth_element(values->begin(), low, values->end());
  return float(*low);
}

// Noise sigma from horizontal neighbours' differences on every fourth row.
template <typename T>
double noise_sigma(const cv::Mat& work, std::vector<int>* values) {
  if constexpr (sizeof(T) == 1) {
    // Four interleaved counts: noise differences fill a few bins, and each count
    // into one table waits for the previous one to the same bin. The differences
    // of 8 pairs at a time with SSE2 (this count was most of a flat frame's
    // flattening check).
    uint32_t counts[4][256] = {};
    size_t n = 0;
    for (int y = 0; y < work.rows; y += 4) {
      const T* row = work.ptr<T>(y);
      int x = 0;
#if defined(__SSE2__)
      for (; x + 16 <= work.cols; x += 16, n += 8) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x));
        const __m128i even = _mm_and_si128(v, _mm_set1_epi16(0x00FF)), odd = _mm_srli_epi16(v, 8);
        const __m128i d = _mm_or_si128(_mm_subs_epu8(even, odd), _mm_subs_epu8(odd, even));  // |row[x + 1] - row[x]|
        ++counts[0][_mm_extract_epi16(d, 0)];
        ++counts[1][_mm_extract_epi16(d, 1)];
        ++counts[2][_mm_extract_epi16(d, 2)];
        ++counts[3][_mm_extract_epi16(d, 3)];
        ++counts[0][_mm_extract_epi16(d, 4)];
        ++counts[1][_mm_extract_epi16(d, 5)];
        ++counts[2][_mm_extract_epi16(d, 6)];
        ++counts[3][_mm_extract_epi16(d, 7)];
      }
#endif
      for (; x + 1 < work.cols; x += 2, ++n) ++counts[0][std::abs(int(row[x + 1]) - int(row[x]))];
    }
    if (n == 0) return 0;
    uint32_t count[256];
    for (int b = 0; b < 256; ++b) count[b] = counts[0][b] + counts[1][b] + counts[2][b] + counts[3][b];
    return 1.4826 * double(rank_in_counts(count, n / 2)) / std::sqrt(2.0);
  }
  values->clear();
  for (int y = 0; y < work.rows; y += 4) {
    const T* row = work.ptr<T>(y);
    for (int x = 0; x + 1 < work.cols; x += 2) values->push_back(std::abs(int(row[x + 1]) - int(row[x])));
  }
  if (values->empty()) return 0;
  auto mid = values->begin() + std::ptrdiff_t(values->size() / 2);
  std::nth_element(values->begin(), mid, values->end());
  return 1.4826 * double(*mid) / std::sqrt(2.0);
}

// The values of ranks k[0] <= k[1] <= k[2] among the pixels of `map` (CV_32F, continuous),
// all of them within [least, greatest] up to rounding: exact, as a sort would
// give, from a histogram of 1024 bins (the bin is monotonic in the value) and a
// selection among the few values of the bin that holds each rank.
void order_statistics(const cv::Mat& map, double least, double greatest, const size_t k[3], float value[3],
                      std::vector<uint16_t>* bin_of_pixel, std::vector<float> in_bin[3]) {
  constexpr int kBins = 1024;
  const float* v = map.ptr<float>();
  const size_t n = map.total();
  const float lo = float(least);
  const float scale = greatest > least ? float((kBins - 1) / (greatest - least)) : 0.0f;
  uint32_t count[kBins] = {};
  bin_of_pixel->resize(n);
  uint16_t* bins = bin_of_pixel->data();
  for (size_t i = 0; i < n; ++i) {
    const float x = std::clamp((v[i] - lo) * scale, 0.0f, float(kBins - 1));
    bins[i] = uint16_t(x);
    ++count[bins[i]];
  }
  // The ranks ascend: one sweep finds the bins of all three.
  int bin[3];
  size_t below[3];
  int b = 0;
  size_t under = 0;
  for (int r = 0; r < 3; ++r) {
    while (under + count[b] <= k[r]) under += count[b++];
    bin[r] = b, below[r] = under;
    in_bin[r].clear();
  }
  // Which ranks each bin holds, as bits (two ranks may share a bin): one lookup a pixel.
  uint8_t ranks_in[kBins] = {};
  for (int r = 0; r < 3; ++r) ranks_in[bin[r]] |= uint8_t(1 << r);
  for (size_t i = 0; i < n; ++i)
    if (const int held = ranks_in[bins[i]])
      for (int r = 0; r < 3; ++r)
        if (held & (1 << r)) in_bin[r].push_back(v[i]);
  for (int r = 0; r < 3; ++r) {
    auto at = in_bin[r].begin() + std::ptrdiff_t(k[r] - below[r]);
    std::nth_element(in_bin[r].begin(), at, in_bin[r].end());
    value[r] = *at;
  }
}

}  // namespace

void BackgroundFlattening::cell_levels(const cv::Mat& work, int cell) {
  // 64 (16-pixel cells) to 256 samples (64-pixel cells) a cell: a percentile of
  // 256 is as good as of 1024, at a quarter of the reads.
  const int step = std::max(2, cell / 16);
  const int nx = (work.cols + cell - 1) / cell, ny = (work.rows + cell - 1) / cell;
  cells_.create(ny, nx, CV_32F);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      cells_.at<float>(j, i) = work.depth() == CV_8U
                                   ? low_of_cell<uint8_t>(work, i * cell, j * cell, cell, step, &values_)
                                   : low_of_cell<uint16_t>(work, i * cell, j * cell, cell, step, &values_);
  if (nx >= 3 && ny >= 3) cv::medianBlur(cells_, cells_, 3);
  // One more cell on every side, extrapolated linearly, so that the map follows a
  // gradient out to the image's edges rather than levelling off half a cell in.
  padded_.create(ny + 2, nx + 2, CV_32F);
  cells_.copyTo(padded_(cv::Rect(1, 1, nx, ny)));
  for (int j = 1; j <= ny; ++j) {
    padded_.at<float>(j, 0) = 2 * padded_.at<float>(j, 1) - padded_.at<float>(j, std::min(2, nx));
    padded_.at<float>(j, nx + 1) = 2 * padded_.at<float>(j, nx) - padded_.at<float>(j, std::max(nx - 1, 1));
  }
  for (int i = 0; i < nx + 2; ++i) {
    padded_.at<float>(0, i) = 2 * padded_.at<float>(1, i) - padded_.at<float>(std::min(2, ny), i);
    padded_.at<float>(ny + 1, i) = 2 * padded_.at<float>(ny, i) - padded_.at<float>(std::max(ny - 1, 1), i);
  }
}

void BackgroundFlattening::upsample(const cv::Mat& work, int cell, int step, cv::Mat* out) {
  // Resized by cell / step, each output pixel is the map at the centre of a step x step block.
  const int scale = cell / step;
  cv::resize(padded_, scaled_, cv::Size(padded_.cols * scale, padded_.rows * scale), 0, 0, cv::INTER_LINEAR);
  scaled_(cv::Rect(scale, scale, (work.cols + step - 1) / step, (work.rows + step - 1) / step)).copyTo(*out);
}

const cv::Mat& BackgroundFlattening::apply(const cv::Mat& work, double saturation) {
  flattened_ = false;
  if (work.cols < 3 * kFineCell || work.rows < 3 * kFineCell) return work;
  const bool eight = work.depth() == CV_8U;
  const double sigma =
      std::max(1.0, eight ? noise_sigma<uint8_t>(work, &values_) : noise_sigma<uint16_t>(work, &values_));
  cell_levels(work, kCoarseCell);
  // Every pixel of the map lies between the least and the greatest padded cell
  // (bilinear weights are convex; the margin covers float rounding): when those
  // span at most 4 sigma so does the map, and the full-size map is not needed.
  double least = 0, greatest = 0;
  cv::minMaxLoc(padded_, &least, &greatest);
  if ((greatest - least) * (1 + 1e-5) + 1e-3 <= 4 * sigma) return work;
  // The 10th, 50th and 90th percentiles of the map, from its values at the centres
  // of 8 x 8 blocks: the map is bilinear over 64-pixel cells, so these stand for
  // its pixels (every pixel cost 80 % of a full frame, a sort of them 92 %).
  upsample(work, kCoarseCell, kPercentileStep, &coarse_);
  const size_t n = coarse_.total(), ranks[3] = {n / 10, n / 2, n * 9 / 10};
  float percentile[3];
  order_statistics(coarse_, least, greatest, ranks, percentile, &bins_, levels_);
  const double spread = percentile[2] - percentile[0];
  if (spread <= 4 * sigma) return work;
  const double median = percentile[1];
  upsample(work, kCoarseCell, 1, &coarse_);
  cell_levels(work, kFineCell);
  upsample(work, kFineCell, 1, &fine_);
  // A large bright object lifts the fine map: it may lie at most 12 sigmas above the coarse one.
  cv::min(fine_, coarse_ + 12 * sigma, fine_);
  out_.create(work.size(), work.type());
  for (int y = 0; y < work.rows; ++y) {
    const float* b = fine_.ptr<float>(y);
    if (eight) {
      const uint8_t* in = work.ptr<uint8_t>(y);
      uint8_t* o = out_.ptr<uint8_t>(y);
      for (int x = 0; x < work.cols; ++x)
        o[x] = in[x] >= saturation ? in[x] : cv::saturate_cast<uint8_t>(in[x] - b[x] + median);
    } else {
      const uint16_t* in = work.ptr<uint16_t>(y);
      uint16_t* o = out_.ptr<uint16_t>(y);
      for (int x = 0; x < work.cols; ++x)
        o[x] = in[x] >= saturation ? in[x] : cv::saturate_cast<uint16_t>(in[x] - b[x] + median);
    }
  }
  flattened_ = true;
  return out_;
}

}  // namespace tetrapulse::blob_internal
