#pragma once
// Internal to BlobExtractor: the recovery steps that turn a rejected region
// into markers (paper Sec. IV-B: "a cascade of recovery methods with
// increasing complexity", and chord bisectors / circles for shadowed blobs).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "blob_regions.hpp"
#include "tetrapulse/localizer/circle_fit.hpp"

namespace tetrapulse::blob_internal {

class BlobRecovery {
 public:
  // Erodes regions[index]'s mask (4-neighbour, up to config.max_erosions times)
  // until it falls into two or more parts, grows the parts back over the
  // original mask (breadth-first, so each pixel joins the part that reaches it
  // first), and measures them. Succeeds when at least two parts pass the
  // tests: they are appended to `regions` (origin kErosionSplit) and the
  // original is marked recovered. Returns the number of parts accepted.
  int split_by_erosion(const cv::Mat& work, cv::Rect window, const Levels& levels, const BlobExtractorConfig& config,
                       RegionGrower* grower, size_t index, std::vector<Region>* regions);

  // Splits regions[index] between `centres` (two or more predicted marker
  // pixels inside it), shifted by the region's weighted centroid minus the
  // centres' mean (the prediction's common error). Flooded from the region's
  // pixel nearest each centre, brightest first, touching lights part at the
  // valley between them (a nearest-centre split cuts a large bright spot at the
  // bisector and hands its dim neighbour a slice of it). Where the floods meet no
  // lower than half the dimmer light's height (no valley: overlapping flat discs,
  // clipped plateaus), when two centres share a pixel, and for pixels no flood
  // reaches, each pixel goes to the nearest centre. The parts are measured and
  // appended, accepted, origin kPredictionSplit, merged; the original is marked
  // recovered. Parts with no pixel are not appended. Returns how many were.
  int split_by_prediction(const cv::Mat& work, cv::Rect window, const Levels& levels, RegionGrower* grower,
                          size_t index, const std::vector<Eigen::Vector2d>& centres, std::vector<Region>* regions);

  // Fits a circle to the rim of `region`: the points where the value crosses
  // half the region's peak between one of its pixels and a 4-neighbour
  // (linear interpolation; a disc's edge or a spot's half-maximum contour),
  // leaving out the window's border (a cut, not rim). RANSAC, Kasa's and the
  // geometric fit, then the ends of a cut arc trimmed and the circle refitted.
  // A circle supported along at least 40 % of its circumference, whose disc
  // holds the region's pixels above that level, replaces the centroid (origin kCircleFit), sets the
  // radius and accepts the region.
  bool fit_circle(const cv::Mat& work, cv::Rect window, const Levels& levels, const BlobExtractorConfig& config,
                  const RegionGrower& grower, Region* region);

 private:
  template <typename T>
  void flood_from(const cv::Mat& work, double background, double sigma, double saturation,
                  const RegionGrower& grower, const Region& region,
                  const std::vector<int>& seeds, const std::vector<Eigen::Vector2d>& centres);
  template <typename T>
  void collect_rim(const cv::Mat& work, cv::Rect window, double level, const RegionGrower& grower,
                   const Region& region);

  std::vector<uint8_t> mask_, eroded_, next_;
  std::vector<int32_t> parts_;
  std::vector<int32_t> cell_, flood_part_;
  std::vector<int> queue_;
  Circle trim_arc_ends(const Circle& circle);

  struct ArcPoint {
    double angle;
    Eigen::Vector2d point;
  };
  std::vector<Eigen::Vector2d> rim_;
  std::vector<ArcPoint> arc_;
  std::vector<Eigen::Vector2d> trimmed_;
  std::vector<Eigen::Vector2d> bright_;  // centres of the region's pixels above the rim level
  std::vector<uint8_t> inliers_;
};

}  // namespace tetrapulse::blob_internal
