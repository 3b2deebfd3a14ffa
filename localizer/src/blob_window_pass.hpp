#pragma once
// Internal to BlobExtractor: the steps both modes run over one window (the
// whole image, or a group of overlapping ROIs), with the scratch memory they
// keep between calls.
#include <cmath>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "background_flattening.hpp"
#include "background_histogram.hpp"
#include "blob_recovery.hpp"
#include "blob_regions.hpp"
#include "blob_working_image.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse::blob_internal {

// Whether `p` lies in the square of `roi` (side 2 x radius about its centre), pixels.
inline bool in_square(const Eigen::Vector2d& p, const BlobRoi& roi) {
  return std::abs(p.x() - roi.center.x()) <= roi.radius && std::abs(p.y() - roi.center.y()) <= roi.radius;
}

// One window: its rectangle, its working image and its levels.
struct Window {
  cv::Rect rect;
  const cv::Mat* work = nullptr;
  Levels levels;
};

class WindowPass {
 public:
  explicit WindowPass(const BlobExtractorConfig& config) : config_(config) {}

  // Starts a call on an image of `size`; finish() unlabels what it labelled.
  void begin(cv::Size size) {
    grower_.reset(size);
    regions_.clear();
  }
  void finish() { grower_.clear(); }

  // Working image, histogram and thresholds of `rect`; appends them to out->windows.
  // `flatten`: a background that is not flat is flattened first (background_flattening.hpp).
  Window prepare(const cv::Mat& image, cv::Rect rect, BlobExtraction* out, bool flatten = false);
  // Grows, measures and tests the regions seeded above `seed_level`; returns
  // the index of the first new one.
  size_t find(const Window& w, double seed_level);
  int accepted() const;
  // More blobs than expected: merge nearly touching pairs, drop isolated ones.
  void prune(int expected);
  // Fewer blobs than expected: the cascade, cheapest first (dim markers,
  // erosion, circle fit); stops once `missing` are found. Blobs centred in the
  // square of one of `measured` (ROIs of this frame, whose own pass split what
  // merged there) are not split again.
  void recover(const Window& w, int missing, const std::vector<BlobRoi>& measured = {});
  // Regions that hold two or more of `centres` (predicted marker pixels) are
  // split between them (BlobRecovery::split_by_prediction).
  void split_by_prediction(const Window& w, const std::vector<Eigen::Vector2d>& centres);
  // Appends the rejected regions (up to config.max_rejected_kept in all).
  void list_rejected(BlobExtraction* out) const;

  std::vector<Region>& regions() { return regions_; }
  // Forgets the regions of the previous window (their labels stay until finish()).
  void next_window() { regions_.clear(); }

 private:
  void measure(const Window& w, Region* r);
  static void reject(Region* r, RejectReason reason, double value);

  BlobExtractorConfig config_;
  WorkingImage working_;
  BackgroundFlattening flattening_;
  BackgroundHistogram histogram_;
  RegionGrower grower_;
  BlobRecovery recovery_;
  std::vector<Region> regions_;
  std::vector<size_t> order_;
  std::vector<double> nearest_;
  std::vector<std::vector<Eigen::Vector2d>> held_;  // centres each region holds
};

}  // namespace tetrapulse::blob_internal
