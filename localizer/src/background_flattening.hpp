#pragma once
// Internal to BlobExtractor: a whole image whose background is not flat (a lit
// floor, sky and shade, a lamp's gradient) has no one background level: a
// threshold above its brightest parts misses markers in its dark parts. Where
// the background's large-scale variation exceeds its noise, the working image
// is flattened: each pixel minus a background map plus the map's median, so
// that one level and one noise hold everywhere.
//   - the map: the 30th percentile of every 16 x 16 cell (of its pixels at even
//     rows and columns: markers are bright, so a cell they partly fill keeps its
//     background's level), a 3 x 3 median over the cells, bilinear between cell
//     centres; where a large bright object lifts it, it is held at most 12 noise
//     sigmas above the same map of 64 x 64 cells (their pixels at every fourth
//     row and column);
//   - flat means: the 64-pixel cells' levels span (10th to 90th percentile) at
//     most 4 noise sigmas, the noise from neighbouring pixels' differences
//     (1.4826 x their median absolute value / sqrt 2);
//   - clipped pixels keep their value, so that saturation is still seen.
// Blob intensities (value - background) are then measured against the local
// background; positions are unchanged.
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace tetrapulse::blob_internal {

class BackgroundFlattening {
 public:
  // `work` (CV_8UC1 or CV_16UC1, markers bright): itself when its background is
  // flat, else the flattened copy (kept until the next call).
  // Pixels at or above `saturation` stay where they are.
  const cv::Mat& apply(const cv::Mat& work, double saturation);
  bool flattened() const { return flattened_; }

 private:
  static constexpr int kFineCell = 16, kCoarseCell = 64, kPercentileStep = 8;
  // The levels of `cell`-sized cells of `work`, one more extrapolated on every
  // side (padded_, CV_32F); then the map (CV_32F) at the centre of every
  // step x step block of `work` (step 1: at every pixel).
  void cell_levels(const cv::Mat& work, int cell);
  void upsample(const cv::Mat& work, int cell, int step, cv::Mat* out);

  cv::Mat cells_, padded_, scaled_, coarse_, fine_, out_;
  std::vector<int> values_;
  std::vector<float> levels_[3];
  std::vector<uint16_t> bins_;
  bool flattened_ = false;
};

}  // namespace tetrapulse::blob_internal
