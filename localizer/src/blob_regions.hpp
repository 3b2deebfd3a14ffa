#pragma once
// Internal to BlobExtractor: connected regions of the working image (markers
// brighter than the background, CV_8UC1 or CV_16UC1), their measurement and
// their acceptance tests.
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "tetrapulse/localizer/blob.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse::blob_internal {

// Levels of one window, grey levels of the working image.
struct Levels {
  double background = 0;
  double sigma = 0;
  double f1 = 0;          // regions grow from values above f1 ...
  double f2 = 0;          // ... over values above f2
  double saturation = 0;  // values at or above it are clipped
  // A sensor often clips below the type's maximum (full well reached before the
  // ADC's top code, or a black level and gain that cap it at 250): a region whose
  // brightest value is shared by kFlatTopPixels pixels or more, at or above this
  // level, is clipped too. Shot noise keeps an unclipped top from being flat.
  double flat_top_floor = 0;
  static constexpr int kFlatTopPixels = 4;
  double reported_background = 0;  // `background` in the input image's grey levels
};

// Sums a region's measurement comes from; two regions merge by adding them.
struct RegionSums {
  int area = 0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;  // moments of pixel centres
  double w = 0, wx = 0, wy = 0;  // (value - background) over the region and its ring
  double peak = 0;               // largest value - background
  double hull_area = 0;          // convex hull of the pixel squares
  bool saturated = false;
  bool clipped = false;
  cv::Rect bbox;

  void merge(const RegionSums& o);
  Blob blob() const;  // all fields but `background` and `origin`
};

struct Region {
  int32_t label = 0;
  int begin = 0, end = 0;  // its pixels: RegionGrower::pixels()[begin, end)
  cv::Rect box;            // their bounding box
  RegionSums sums;
  Blob blob;
  bool accepted = false;   // reported as a blob
  bool rejected = false;   // failed a test or was pruned: `reason`, `reason_value`
  bool recovered = false;  // rejected, then reported by a recovery step (itself or its parts)
  bool quiet = false;      // neither reported nor listed as rejected (surplus of a recovery pass)
  RejectReason reason = RejectReason::kTooSmall;
  double reason_value = 0;
};

// Sets region->accepted, or region->rejected with reason and reason_value.
void classify(const BlobExtractorConfig& config, Region* region);

// A corner of a pixel square, both coordinates doubled (whole numbers).
struct HullPoint {
  int64_t y, x;
};

// Labels of one image; a region's pixels are listed as y * width + x.
class RegionGrower {
 public:
  // Labels all zero for images of `size` (allocates only when the size changes).
  void reset(cv::Size size);
  // Unlabels every pixel labelled since reset().
  void clear();

  // Appends every 8-connected region of values > levels.f2 inside `window`
  // that holds a value > seed_level and is not yet labelled.
  void grow(const cv::Mat& work, cv::Rect window, const Levels& levels, double seed_level,
            std::vector<Region>* regions);

  // Measures `region` (its pixels, plus the unlabelled pixels next to them in
  // `window`) and fills region->sums and region->blob.
  void measure(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region);

  int width() const { return size_.width; }
  int32_t new_label() { return next_label_++; }
  int32_t label(int index) const { return labels_[size_t(index)]; }
  void set_label(int index, int32_t label) { labels_[size_t(index)] = label; }
  std::vector<int32_t>& pixels() { return pixels_; }
  const std::vector<int32_t>& pixels() const { return pixels_; }

 private:
  template <typename T>
  void grow_typed(const cv::Mat& work, cv::Rect window, int seed_min, int keep_min, bool masked,
                  std::vector<Region>* regions);
  // 8-bit windows 16..kMaxBitsWidth wide (ROI windows): rows of the window as bits.
  static constexpr int kMaxBitsWidth = 62;      // a row's bits shifted left once still fit 64
  static constexpr int kMaxBitsHeight = 0xFFFF;  // grow_bits packs a row number in 16 bits
  void grow_narrow(const cv::Mat& work, cv::Rect window, int seed_min, int keep_min, std::vector<Region>* regions);
  // Grows the region of the open pixel (window.x + c, window.y + r) from open_rows_:
  // the pixels grow_from would take, in the same order.
  void grow_bits(cv::Rect window, int c, int r, std::vector<Region>* regions);
  template <typename T>
  void grow_from(const cv::Mat& work, cv::Rect window, int seed, int keep_min, std::vector<Region>* regions);
  template <typename T>
  void measure_typed(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region);

  cv::Size size_;
  std::vector<int32_t> labels_;
  std::vector<int32_t> pixels_;
  std::vector<std::pair<int, int>> queue_;  // (x, y) of a growing region's pixels, in the order reached
  cv::Mat seed_mask_;  // pixels at or above the seed level (large windows)
  // grow_narrow's window rows (bit i: x = window.x + i): seeds, and pixels above
  // f2 not labelled yet (cleared as they are taken).
  std::vector<uint64_t> seed_rows_, open_rows_;
  std::vector<uint32_t> bits_queue_;  // grow_bits' pixels, c | r << 16 in the window
  int32_t next_label_ = 1;
  std::vector<int> row_min_, row_max_;
  std::vector<uint64_t> member_rows_;  // measure's rows of a region as bits
  std::vector<HullPoint> hull_points_, hull_;
};

}  // namespace tetrapulse::blob_internal
