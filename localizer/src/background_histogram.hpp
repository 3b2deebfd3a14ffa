#pragma once
// Internal to BlobExtractor: the grey-level histogram of one window and the
// two statistics the thresholds come from (background Gaussian, Otsu).
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace tetrapulse::blob_internal {

struct BackgroundFit {
  double mean = 0;   // grey levels
  double sigma = 0;  // grey levels (before any floor)
};

class BackgroundHistogram {
 public:
  // Counts the values of `image` (CV_8UC1 or CV_16UC1) inside `window`, which
  // must lie in the image; of 8-bit windows of 65536 pixels or more, every other
  // row (on x86-64, the 8 levels that hold most of the first row 16 pixels at a
  // time). 16-bit values share bins (at most 4096) by a shift.
  void count(const cv::Mat& image, cv::Rect window);

  // Gaussian fitted to the background peak: starts at the histogram's mode with
  // sigma from its half-maximum width (both read with neighbouring bins merged
  // until the tallest holds enough pixels to be a peak), then re-estimates mean
  // and sigma from the bins within 3 sigma (truncation and bin-width corrected)
  // until stable.
  // The foreground, far in one tail, does not enter. Nor do clipped pixels: a
  // saturated marker larger than the background's share of the window piles up
  // in one bin, the tallest, yet it is no background. The mode is sought below
  // that pile-up: the top occupied bin when its values reach `saturation` (grey
  // levels), or when it holds at least 4 pixels and 4x the next occupied bin
  // below (a sensor that clips under the type's top code).
  BackgroundFit fit_background(double saturation) const;

  // Otsu's threshold: values above it form the brighter class; -1 when the
  // window holds a single value.
  double otsu() const;

  int bin_width() const { return 1 << shift_; }
  // Pixels counted in `bin` (0 <= bin < bins in use: 256 for 8-bit data).
  uint32_t bin_count(int bin) const { return bins_[size_t(bin)]; }
  uint32_t total() const { return total_; }  // pixels counted

 private:
  // Mean of the values a bin can hold: multiples of the data's quantum.
  double bin_centre(double bin) const { return bin * (1 << shift_) + ((1 << shift_) - quantum_) * 0.5; }

  // The first and last occupied bins within [from, to] (lo_ > hi_: none there).
  void find_occupied(int from, int to);

  std::vector<uint32_t> bins_;
  std::vector<uint32_t> partial_;  // 4 or 8 interleaved 8-bit histograms (fewer store-to-load stalls)
  std::vector<uint32_t> full_;     // every 16-bit value (large windows)
  mutable std::vector<uint32_t> merged_;  // fit_background's scratch: neighbouring bins merged
  int used_ = 0;                   // bins in use
  int lo_ = 0, hi_ = -1;           // the first and last occupied bins
  int shift_ = 0;
  int quantum_ = 1;  // step between the values the data holds (16-bit data from a 10- or 12-bit sensor)
  uint32_t total_ = 0;
};

}  // namespace tetrapulse::blob_internal
