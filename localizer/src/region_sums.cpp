// A region's sums turned into a blob, and the blob's acceptance tests.
#include <algorithm>
#include <cmath>

#include "blob_regions.hpp"

namespace tetrapulse::blob_internal {

void RegionSums::merge(const RegionSums& o) {
  area += o.area;
  sx += o.sx;
  sy += o.sy;
  sxx += o.sxx;
  sxy += o.sxy;
  syy += o.syy;
  w += o.w;
  wx += o.wx;
  wy += o.wy;
  peak = std::max(peak, o.peak);
  hull_area += o.hull_area;  // not the hull of the union: merged blobs keep their own convexity
  saturated = saturated || o.saturated;
  clipped = clipped || o.clipped;
  bbox = bbox | o.bbox;
}

Blob RegionSums::blob() const {
  Blob b;
  b.area = area;
  b.bbox = bbox;
  b.peak = peak;
  b.saturated = saturated;
  b.clipped = clipped;
  b.intensity = w;
  if (area <= 0) return b;
  const double n = area;
  const Eigen::Vector2d mean(sx / n, sy / n);
  b.centroid = w > 0 ? Eigen::Vector2d(wx / w, wy / w) : mean;
  b.radius = std::sqrt(n / M_PI);
  // Second moments of the pixel squares (a pixel adds 1/12 on each axis).
  const double cxx = std::max(0.0, sxx / n - mean.x() * mean.x()) + 1.0 / 12.0;
  const double cyy = std::max(0.0, syy / n - mean.y() * mean.y()) + 1.0 / 12.0;
  const double cxy = sxy / n - mean.x() * mean.y();
  const double half_sum = 0.5 * (cxx + cyy);
  const double root = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
  const double big = half_sum + root, small = std::max(0.0, half_sum - root);
  b.eccentricity = big > 0 ? std::sqrt(std::max(0.0, 1.0 - small / big)) : 0.0;
  // Major axis within 15 degrees of y: 2 theta within 30 degrees of 180.
  constexpr double kTan30 = 0.57735026918962573;
  b.bloomed = saturated && cyy > cxx && 2 * std::abs(cxy) <= kTan30 * (cyy - cxx);
  b.convexity = hull_area > 0 ? std::min(1.0, n / hull_area) : 1.0;
  return b;
}

void classify(const BlobExtractorConfig& config, Region* region) {
  const Blob& b = region->blob;
  const bool judge_shape = b.area >= config.min_shape_area;
  region->accepted = false;
  region->rejected = true;
  if (b.area < config.min_area) {
    region->reason = RejectReason::kTooSmall;
    region->reason_value = b.area;
  } else if (b.area > config.max_area) {
    region->reason = RejectReason::kTooLarge;
    region->reason_value = b.area;
  } else if (judge_shape && b.convexity < config.min_convexity) {
    region->reason = RejectReason::kNonConvex;
    region->reason_value = b.convexity;
  } else if (judge_shape && b.eccentricity > config.max_eccentricity && !b.bloomed) {
    region->reason = RejectReason::kEccentric;
    region->reason_value = b.eccentricity;
  } else {
    region->accepted = true;
    region->rejected = false;
  }
}

}  // namespace tetrapulse::blob_internal
