#include "blob_recovery.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace tetrapulse::blob_internal {
namespace {

constexpr int kMaxCropSide = 256;  // larger regions are not worth a split (and would be slow)

// 8-connected components of `mask` (w x h); labels 1..n in `parts`. Returns n.
int label_parts(const std::vector<uint8_t>& mask, int w, int h, std::vector<int32_t>* parts, std::vector<int>* queue) {
  parts->assign(mask.size(), 0);
  int count = 0;
  for (int start = 0; start < w * h; ++start) {
    if (!mask[size_t(start)] || (*parts)[size_t(start)]) continue;
    ++count;
    queue->clear();
    queue->push_back(start);
    (*parts)[size_t(start)] = count;
    for (size_t head = 0; head < queue->size(); ++head) {
      const int i = (*queue)[head], y = i / w, x = i - y * w;
      for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, h - 1); ++ny)
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, w - 1); ++nx) {
          const int n = ny * w + nx;
          if (!mask[size_t(n)] || (*parts)[size_t(n)]) continue;
          (*parts)[size_t(n)] = count;
          queue->push_back(n);
        }
    }
  }
  return count;
}

}  // namespace

template <typename T>
void BlobRecovery::flood_from(const cv::Mat& work, double background, double sigma, double saturation,
                              const RegionGrower& grower, const Region& region, const std::vector<int>& seeds,
                              const std::vector<Eigen::Vector2d>& centres) {
  // Distinct seeds only; otherwise the nearest-centre parts stand.
  for (size_t a = 0; a < seeds.size(); ++a)
    for (size_t b = a + 1; b < seeds.size(); ++b)
      if (seeds[a] < 0 || seeds[a] == seeds[b]) return;
  const cv::Rect box = region.sums.bbox;
  if (box.width > kMaxCropSide || box.height > kMaxCropSide || box.area() <= 0) return;
  const int width = grower.width();
  const int n = region.end - region.begin;
  // The crop's cells: the region's pixel index (from begin) or -1.
  cell_.assign(size_t(box.area()), -1);
  for (int i = 0; i < n; ++i) {
    const int p = grower.pixels()[size_t(region.begin + i)], y = p / width, x = p - y * width;
    cell_[size_t((y - box.y) * box.width + (x - box.x))] = i;
  }
  // Flooding from the seeds, brightest pixel first: each part grows down its own
  // slope, and the parts meet at the valley between the lights, not where the
  // centres' bisector happens to cut. A pixel goes to the part that reaches it at
  // the highest level; at one level (a plateau) to the part whose centre is
  // nearer.
  struct Entry {
    double value;
    double distance;  // from the pixel to its part's centre
    int pixel;
    int32_t part;
    bool operator<(const Entry& o) const { return value < o.value || (value == o.value && distance > o.distance); }
  };
  std::vector<int32_t>& part = flood_part_;
  part.assign(size_t(n), -1);
  std::priority_queue<Entry> queue;
  const auto xy = [&](int i) {
    const int p = grower.pixels()[size_t(region.begin + i)], y = p / width;
    return Eigen::Vector2d(p - y * width, y);
  };
  const auto value_of = [&](int i) {
    const int p = grower.pixels()[size_t(region.begin + i)], y = p / width, x = p - y * width;
    return double(work.ptr<T>(y)[x]);
  };
  // Noise, not light: a step up of a few sigma plus a twentieth of the height.
  const auto uphill = [&](double level) { return 4 * sigma + 0.05 * std::max(0.0, level - background); };
  for (size_t k = 0; k < seeds.size(); ++k) queue.push({value_of(seeds[k]), 0.0, seeds[k], int32_t(k)});
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    if (part[size_t(e.pixel)] >= 0) continue;
    part[size_t(e.pixel)] = e.part;
    const Eigen::Vector2d q = xy(e.pixel);
    const int x = int(q.x()), y = int(q.y());
    for (int ny = std::max(y - 1, box.y); ny <= std::min(y + 1, box.y + box.height - 1); ++ny)
      for (int nx = std::max(x - 1, box.x); nx <= std::min(x + 1, box.x + box.width - 1); ++nx) {
        const int j = cell_[size_t((ny - box.y) * box.width + (nx - box.x))];
        if (j < 0 || part[size_t(j)] >= 0) continue;
        // Clipped, and clearly brighter than the level this light has come down
        // to: another light adds to it (the lens where two discs overlap). Not this
        // flood's; if no flood comes down to it, the nearest centre takes it.
        const double v = value_of(j);
        if (v >= saturation && v > e.value + uphill(e.value)) continue;
        queue.push({std::min(v, e.value), (Eigen::Vector2d(nx, ny) - centres[size_t(e.part)]).norm(), j, e.part});
      }
  }
  for (int i = 0; i < n; ++i)
    if (part[size_t(i)] >= 0) parts_[size_t(i)] = part[size_t(i)];
}

int BlobRecovery::split_by_prediction(const cv::Mat& work, cv::Rect window, const Levels& levels,
                                      RegionGrower* grower, size_t index, const std::vector<Eigen::Vector2d>& centres,
                                      std::vector<Region>* regions) {
  const Region original = (*regions)[index];
  if (centres.size() < 2 || original.end <= original.begin) return 0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& c : centres) mean += c;
  const int width = grower->width();
  const Eigen::Vector2d shift = original.blob.centroid - mean / double(centres.size());
  const size_t first = regions->size();
  parts_.assign(size_t(original.end - original.begin), 0);
  std::vector<Eigen::Vector2d> shifted;
  for (const Eigen::Vector2d& c : centres) shifted.push_back(c + shift);
  std::vector<int> seeds(centres.size(), -1);
  // the region's pixel (index from begin) nearest each centre
  std::vector<double> seed_distance(centres.size(), std::numeric_limits<double>::infinity());
  for (int i = original.begin; i < original.end; ++i) {
    const int p = grower->pixels()[size_t(i)], y = p / width, x = p - y * width;
    int nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < centres.size(); ++k) {
      const double d = (Eigen::Vector2d(x, y) - centres[k] - shift).squaredNorm();
      if (d < best) best = d, nearest = int(k);
      if (d < seed_distance[k]) seed_distance[k] = d, seeds[k] = i - original.begin;
    }
    parts_[size_t(i - original.begin)] = nearest;
  }
  if (work.depth() == CV_8U) {
    flood_from<uint8_t>(work, levels.background, levels.sigma, levels.saturation, *grower, original, seeds, shifted);
  } else {
    flood_from<uint16_t>(work, levels.background, levels.sigma, levels.saturation, *grower, original, seeds, shifted);
  }
  for (size_t k = 0; k < centres.size(); ++k) {
    Region r;
    r.label = grower->new_label();
    r.begin = static_cast<int>(grower->pixels().size());
    for (int i = original.begin; i < original.end; ++i) {
      if (parts_[size_t(i - original.begin)] != int(k)) continue;
      const int p = grower->pixels()[size_t(i)], y = p / width, x = p - y * width;
      grower->pixels().push_back(p);
      r.box |= cv::Rect(x, y, 1, 1);
    }
    r.end = static_cast<int>(grower->pixels().size());
    if (r.end > r.begin) regions->push_back(r);
  }
  // Labelled only once all are listed, so that each part's ring leaves out the others.
  for (size_t k = first; k < regions->size(); ++k)
    for (int i = (*regions)[k].begin; i < (*regions)[k].end; ++i)
      grower->set_label(grower->pixels()[size_t(i)], (*regions)[k].label);
  for (size_t k = first; k < regions->size(); ++k) {
    Region& r = (*regions)[k];
    grower->measure(work, window, levels, &r);
    r.blob.origin = BlobOrigin::kPredictionSplit;
    r.blob.merged = true;
    r.blob.merge_group = original.label;
    r.blob.merge_parts = static_cast<int>(regions->size() - first);
    r.accepted = true;
  }
  Region& split = (*regions)[index];
  split.accepted = false;
  split.rejected = true;
  split.recovered = true;
  split.reason = RejectReason::kMerged;
  split.reason_value = double(centres.size());
  return static_cast<int>(regions->size() - first);
}

int BlobRecovery::split_by_erosion(const cv::Mat& work, cv::Rect window, const Levels& levels,
                                   const BlobExtractorConfig& config, RegionGrower* grower, size_t index,
                                   std::vector<Region>* regions) {
  const Region original = (*regions)[index];
  const cv::Rect box = original.sums.bbox;
  if (box.width > kMaxCropSide || box.height > kMaxCropSide || original.end <= original.begin) return 0;
  // The crop has a one-pixel empty frame, so erosion needs no bounds checks.
  const int w = box.width + 2, h = box.height + 2, ox = box.x - 1, oy = box.y - 1;
  const int width = grower->width();
  mask_.assign(size_t(w) * h, 0);
  for (int i = original.begin; i < original.end; ++i) {
    const int p = grower->pixels()[size_t(i)], y = p / width, x = p - y * width;
    mask_[size_t(y - oy) * w + (x - ox)] = 1;
  }
  eroded_ = mask_;
  for (int step = 0; step < config.max_erosions; ++step) {
    next_.assign(eroded_.size(), 0);
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        const size_t i = size_t(y) * w + x;
        next_[i] = eroded_[i] && eroded_[i - 1] && eroded_[i + 1] && eroded_[i - w] && eroded_[i + w];
      }
    eroded_.swap(next_);
    const int count = label_parts(eroded_, w, h, &parts_, &queue_);
    if (count == 0) return 0;
    if (count < 2) continue;

    // Grow the parts back over the original mask, all at once, layer by layer.
    queue_.clear();
    for (int i = 0; i < w * h; ++i)
      if (parts_[size_t(i)]) queue_.push_back(i);
    for (size_t head = 0; head < queue_.size(); ++head) {
      const int i = queue_[head], y = i / w, x = i - y * w;
      for (int ny = y - 1; ny <= y + 1; ++ny)
        for (int nx = x - 1; nx <= x + 1; ++nx) {
          const int n = ny * w + nx;
          if (!mask_[size_t(n)] || parts_[size_t(n)]) continue;
          parts_[size_t(n)] = parts_[size_t(i)];
          queue_.push_back(n);
        }
    }

    const size_t first = regions->size();
    for (int part = 1; part <= count; ++part) {
      Region r;
      r.label = grower->new_label();
      r.begin = static_cast<int>(grower->pixels().size());
      for (int i = 0; i < w * h; ++i) {
        if (parts_[size_t(i)] != part) continue;
        const int y = i / w, x = i - y * w;
        const int p = (y + oy) * width + (x + ox);
        grower->set_label(p, r.label);
        grower->pixels().push_back(p);
        r.box |= cv::Rect(x + ox, y + oy, 1, 1);
      }
      r.end = static_cast<int>(grower->pixels().size());
      regions->push_back(r);
    }
    int accepted = 0;
    for (size_t k = first; k < regions->size(); ++k) {
      Region& r = (*regions)[k];
      grower->measure(work, window, levels, &r);
      classify(config, &r);
      r.blob.origin = BlobOrigin::kErosionSplit;
      r.quiet = !r.accepted;  // a crumb of a split is not a candidate of its own
      accepted += r.accepted;
    }
    if (accepted >= 2) {
      (*regions)[index].recovered = true;
      return accepted;
    }
    // Not two markers: give the pixels back and forget the parts.
    for (size_t k = first; k < regions->size(); ++k) {
      const Region& r = (*regions)[k];
      for (int i = r.begin; i < r.end; ++i) grower->set_label(grower->pixels()[size_t(i)], original.label);
    }
    regions->resize(first);
    return 0;
  }
  return 0;
}

template <typename T>
void BlobRecovery::collect_rim(const cv::Mat& work, cv::Rect window, double level, const RegionGrower& grower,
                               const Region& region) {
  const int width = grower.width();
  const int x0 = window.x, x1 = window.x + window.width - 1, y0 = window.y, y1 = window.y + window.height - 1;
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  rim_.clear();
  bright_.clear();
  for (int i = region.begin; i < region.end; ++i) {
    const int p = grower.pixels()[size_t(i)], y = p / width, x = p - y * width;
    const double v = work.ptr<T>(y)[x];
    if (v < level) continue;
    bright_.emplace_back(x, y);
    for (int d = 0; d < 4; ++d) {
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx < x0 || nx > x1 || ny < y0 || ny > y1) continue;  // cut by the window: not rim
      const double u = work.ptr<T>(ny)[nx];
      if (u >= level) continue;
      const double t = (v - level) / (v - u);
      rim_.emplace_back(x + t * kDx[d], y + t * kDy[d]);
    }
  }
}

Circle BlobRecovery::trim_arc_ends(const Circle& circle) {
  // Rim pixels next to the cut are partly cut too, so the arc's last points
  // lie inside the circle. Where the supporting points leave a gap (a cut arc),
  // those within 1.5 px of either end are dropped and the circle refitted.
  arc_.clear();
  for (size_t i = 0; i < rim_.size(); ++i) {
    if (!inliers_[i]) continue;
    const Eigen::Vector2d d = rim_[i] - circle.center;
    arc_.push_back({std::atan2(d.y(), d.x()), rim_[i]});
  }
  if (arc_.size() < 8) return circle;
  std::sort(arc_.begin(), arc_.end(), [](const ArcPoint& a, const ArcPoint& b) { return a.angle < b.angle; });
  size_t after_gap = 0;
  double gap = arc_.front().angle + 2 * M_PI - arc_.back().angle;
  for (size_t i = 1; i < arc_.size(); ++i) {
    if (arc_[i].angle - arc_[i - 1].angle > gap) {
      gap = arc_[i].angle - arc_[i - 1].angle;
      after_gap = i;
    }
  }
  if (gap < M_PI / 4) return circle;  // a whole circle: no ends
  const double start = arc_[after_gap].angle;
  const double end = arc_[(after_gap + arc_.size() - 1) % arc_.size()].angle;
  const double trim = 1.5 / circle.radius;  // radians
  trimmed_.clear();
  for (const ArcPoint& a : arc_) {
    const double from_start = std::remainder(a.angle - start, 2 * M_PI);
    const double to_end = std::remainder(end - a.angle, 2 * M_PI);
    if (std::abs(from_start) > trim && std::abs(to_end) > trim) trimmed_.push_back(a.point);
  }
  if (trimmed_.size() < 6) return circle;
  return fit_circle_geometric(trimmed_.data(), trimmed_.size(), circle).value_or(circle);
}

bool BlobRecovery::fit_circle(const cv::Mat& work, cv::Rect window, const Levels& levels,
                              const BlobExtractorConfig& config, const RegionGrower& grower, Region* region) {
  const double level = levels.background + config.circle_rim_fraction * region->sums.peak;
  if (work.depth() == CV_8U) {
    collect_rim<uint8_t>(work, window, level, grower, *region);
  } else {
    collect_rim<uint16_t>(work, window, level, grower, *region);
  }
  RobustCircleOptions options;
  options.inlier_tolerance = config.circle_inlier_px;
  options.trials = config.circle_trials;
  options.min_radius = 1.0;
  options.max_radius = 1.5 * std::sqrt(std::max(config.max_area, 1) / M_PI);
  const auto fit = fit_circle_robust(rim_.data(), rim_.size(), options, &inliers_);
  if (!fit) return false;
  const Circle c = trim_arc_ends(fit->circle);
  // A digital circle of radius r crosses about 8 r pixel edges.
  const bool supported = fit->inliers >= std::max(8.0, 0.4 * 8.0 * c.radius);
  // The pixels above the rim level must lie in the disc: a circle on one lobe
  // of a larger blob does not describe the blob.
  const double reach = c.radius + 0.75;
  const auto inside = std::count_if(bright_.begin(), bright_.end(), [&](const Eigen::Vector2d& p) {
    return (p - c.center).squaredNorm() <= reach * reach;
  });
  const bool holds_region = double(inside) >= 0.95 * double(bright_.size());
  const cv::Rect& box = region->sums.bbox;
  const bool near = c.center.x() >= box.x - c.radius && c.center.x() <= box.x + box.width + c.radius &&
                    c.center.y() >= box.y - c.radius && c.center.y() <= box.y + box.height + c.radius;
  if (!supported || !holds_region || !near) return false;
  region->blob.centroid = c.center;
  region->blob.radius = c.radius;
  region->blob.origin = BlobOrigin::kCircleFit;
  region->accepted = true;
  region->recovered = region->rejected;
  return true;
}

}  // namespace tetrapulse::blob_internal
