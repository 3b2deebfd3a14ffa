#include "blob_regions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetrapulse::blob_internal {
namespace {

// Smallest integer value v with v > level, clamped to what an int holds.
int above(double level) {
  if (!(level < 1e9)) return std::numeric_limits<int>::max();
  if (level < -1e9) return std::numeric_limits<int>::min();
  return static_cast<int>(std::floor(level)) + 1;
}

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Area of the convex hull of `points` (Andrew's monotone chain); sorts them.
double convex_hull_area(std::vector<Eigen::Vector2d>* points, std::vector<Eigen::Vector2d>* hull) {
  auto& p = *points;
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return 0.0;
  hull->assign(2 * p.size(), Eigen::Vector2d::Zero());
  auto& h = *hull;
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  double twice = 0;
  for (size_t i = 0; i + 1 < k; ++i) twice += h[i].x() * h[i + 1].y() - h[i + 1].x() * h[i].y();
  return 0.5 * std::abs(twice);
}

}  // namespace

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
  } else if (judge_shape && b.eccentricity > config.max_eccentricity) {
    region->reason = RejectReason::kEccentric;
    region->reason_value = b.eccentricity;
  } else {
    region->accepted = true;
    region->rejected = false;
  }
}

void RegionGrower::reset(cv::Size size) {
  if (size != size_) {
    size_ = size;
    labels_.assign(size_t(std::max(0, size.area())), 0);
  } else {
    clear();
  }
  pixels_.clear();
  next_label_ = 1;
}

void RegionGrower::clear() {
  for (const int32_t index : pixels_) labels_[size_t(index)] = 0;
  pixels_.clear();
}

void RegionGrower::grow(const cv::Mat& work, cv::Rect window, const Levels& levels, double seed_level,
                        std::vector<Region>* regions) {
  const int seed_min = above(std::max(seed_level, levels.f2));
  const int keep_min = above(levels.f2);
  if (work.depth() == CV_8U) {
    grow_typed<uint8_t>(work, window, seed_min, keep_min, regions);
  } else {
    grow_typed<uint16_t>(work, window, seed_min, keep_min, regions);
  }
}

template <typename T>
void RegionGrower::grow_typed(const cv::Mat& work, cv::Rect window, int seed_min, int keep_min,
                              std::vector<Region>* regions) {
  const int width = size_.width;
  const int x0 = window.x, x1 = window.x + window.width;
  const int y0 = window.y, y1 = window.y + window.height;
  for (int y = y0; y < y1; ++y) {
    const T* row = work.ptr<T>(y);
    const int32_t* labels = labels_.data() + size_t(y) * width;
    for (int x = x0; x < x1; ++x) {
      if (row[x] < seed_min || labels[x] != 0) continue;
      Region region;
      region.label = next_label_++;
      region.begin = static_cast<int>(pixels_.size());
      labels_[size_t(y) * width + x] = region.label;
      pixels_.push_back(y * width + x);
      // Breadth-first: the pixel list is also the queue.
      for (size_t head = size_t(region.begin); head < pixels_.size(); ++head) {
        const int index = pixels_[head];
        const int py = index / width, px = index - py * width;
        for (int ny = std::max(py - 1, y0); ny <= std::min(py + 1, y1 - 1); ++ny) {
          const T* nrow = work.ptr<T>(ny);
          for (int nx = std::max(px - 1, x0); nx <= std::min(px + 1, x1 - 1); ++nx) {
            const int n = ny * width + nx;
            if (labels_[size_t(n)] != 0 || nrow[nx] < keep_min) continue;
            labels_[size_t(n)] = region.label;
            pixels_.push_back(n);
          }
        }
      }
      region.end = static_cast<int>(pixels_.size());
      regions->push_back(region);
    }
  }
}

void RegionGrower::measure(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region) {
  if (work.depth() == CV_8U) {
    measure_typed<uint8_t>(work, window, levels, region);
  } else {
    measure_typed<uint16_t>(work, window, levels, region);
  }
}

template <typename T>
void RegionGrower::measure_typed(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region) {
  const int width = size_.width;
  const double bg = levels.background;
  RegionSums s;
  int min_x = std::numeric_limits<int>::max(), max_x = -1, min_y = std::numeric_limits<int>::max(), max_y = -1;
  s.peak = -std::numeric_limits<double>::infinity();
  for (int i = region->begin; i < region->end; ++i) {
    const int index = pixels_[size_t(i)];
    const int y = index / width, x = index - y * width;
    const double v = work.ptr<T>(y)[x];
    const double d = v - bg;
    ++s.area;
    s.sx += x;
    s.sy += y;
    s.sxx += double(x) * x;
    s.sxy += double(x) * y;
    s.syy += double(y) * y;
    s.w += d;
    s.wx += d * x;
    s.wy += d * y;
    s.peak = std::max(s.peak, d);
    s.saturated = s.saturated || v >= levels.saturation;
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  }
  if (s.area == 0) {
    region->sums = s;
    region->blob = s.blob();
    return;
  }
  s.bbox = cv::Rect(min_x, min_y, max_x - min_x + 1, max_y - min_y + 1);
  s.clipped = min_x == window.x || min_y == window.y || max_x == window.x + window.width - 1 ||
              max_y == window.y + window.height - 1;

  // The ring: unlabelled pixels touching the region hold the spot's faint tail.
  const int rx0 = std::max(min_x - 1, window.x), rx1 = std::min(max_x + 1, window.x + window.width - 1);
  const int ry0 = std::max(min_y - 1, window.y), ry1 = std::min(max_y + 1, window.y + window.height - 1);
  for (int y = ry0; y <= ry1; ++y) {
    const T* row = work.ptr<T>(y);
    for (int x = rx0; x <= rx1; ++x) {
      if (labels_[size_t(y) * width + x] != 0) continue;
      bool touches = false;
      for (int ny = std::max(y - 1, ry0); ny <= std::min(y + 1, ry1) && !touches; ++ny)
        for (int nx = std::max(x - 1, rx0); nx <= std::min(x + 1, rx1); ++nx)
          if (labels_[size_t(ny) * width + nx] == region->label) {
            touches = true;
            break;
          }
      const double d = double(row[x]) - bg;
      if (!touches || d <= 0) continue;
      s.w += d;
      s.wx += d * x;
      s.wy += d * y;
    }
  }

  // Convex hull of the pixel squares, from each row's extent.
  const int rows = s.bbox.height;
  row_min_.assign(size_t(rows), std::numeric_limits<int>::max());
  row_max_.assign(size_t(rows), -1);
  for (int i = region->begin; i < region->end; ++i) {
    const int index = pixels_[size_t(i)];
    const int y = index / width, x = index - y * width;
    row_min_[size_t(y - min_y)] = std::min(row_min_[size_t(y - min_y)], x);
    row_max_[size_t(y - min_y)] = std::max(row_max_[size_t(y - min_y)], x);
  }
  hull_points_.clear();
  for (int r = 0; r < rows; ++r) {
    if (row_max_[size_t(r)] < 0) continue;
    const double left = row_min_[size_t(r)] - 0.5, right = row_max_[size_t(r)] + 0.5, y = min_y + r;
    hull_points_.emplace_back(left, y - 0.5);
    hull_points_.emplace_back(right, y - 0.5);
    hull_points_.emplace_back(left, y + 0.5);
    hull_points_.emplace_back(right, y + 0.5);
  }
  s.hull_area = convex_hull_area(&hull_points_, &hull_);
  region->sums = s;
  region->blob = s.blob();
}

}  // namespace tetrapulse::blob_internal
