#include "blob_window_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetrapulse::blob_internal {
namespace {

double type_max(const cv::Mat& image) { return image.depth() == CV_16U ? 65535.0 : 255.0; }

// The input's grey level for a working level (dark markers are inverted).
double to_input(double level, const cv::Mat& image, const BlobExtractorConfig& config) {
  const bool inverted = config.polarity == MarkerPolarity::kDark && !config.colour;
  return inverted ? type_max(image) - level : level;
}

bool reason_is_shape(RejectReason r) {
  return r == RejectReason::kNonConvex || r == RejectReason::kEccentric || r == RejectReason::kTooLarge;
}

}  // namespace

Window WindowPass::prepare(const cv::Mat& image, cv::Rect rect, BlobExtraction* out, bool flatten) {
  Window w;
  w.rect = rect;
  w.work = &working_.prepare(image, rect, config_.polarity, config_.colour);
  const bool inverted = config_.polarity == MarkerPolarity::kDark && !config_.colour;
  const double top = image.channels() == 3 ? 255.0 : type_max(image);
  const double saturation = inverted || config_.saturation_level <= 0 ? top : config_.saturation_level;
  if (flatten) w.work = &flattening_.apply(*w.work, saturation);
  histogram_.count(*w.work, rect);
  const BackgroundFit fit = histogram_.fit_background(saturation);
  Levels& lv = w.levels;
  lv.background = fit.mean;
  lv.sigma = std::max({fit.sigma, config_.min_background_sigma, 0.5 * histogram_.bin_width()});
  lv.f2 = lv.background + config_.f2_sigmas * lv.sigma;
  lv.f1 = std::max({histogram_.otsu(), lv.background + config_.f1_min_sigmas * lv.sigma, lv.f2});
  lv.saturation = saturation;
  // 8-bit sensors clip at 240-255; deeper containers may hold 10-16 bits unshifted.
  lv.flat_top_floor = w.work->depth() == CV_8U ? 0.75 * 255 : lv.f1;
  lv.reported_background = to_input(lv.background, image, config_);
  WindowThresholds t;
  t.window = rect;
  t.background = lv.reported_background;
  t.background_sigma = lv.sigma;
  t.f1 = to_input(lv.f1, image, config_);
  t.f2 = to_input(lv.f2, image, config_);
  out->windows.push_back(t);
  return w;
}

size_t WindowPass::find(const Window& w, double seed_level) {
  const size_t first = regions_.size();
  grower_.grow(*w.work, w.rect, w.levels, seed_level, &regions_);
  for (size_t i = first; i < regions_.size(); ++i) measure(w, &regions_[i]);
  return first;
}

int WindowPass::accepted() const {
  return static_cast<int>(
      std::count_if(regions_.begin(), regions_.end(), [](const Region& r) { return r.accepted; }));
}

void WindowPass::prune(int expected) {
  auto& order = order_;
  order.clear();
  for (size_t i = 0; i < regions_.size(); ++i)
    if (regions_[i].accepted) order.push_back(i);
  // Far too many (clutter): keep the brightest few before the quadratic pruning.
  const size_t cap = size_t(4 * expected + 32);
  if (order.size() > cap) {
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return regions_[a].blob.intensity > regions_[b].blob.intensity;
    });
    for (size_t k = cap; k < order.size(); ++k) reject(&regions_[order[k]], RejectReason::kFaint,
                                                        regions_[order[k]].blob.intensity);
    order.resize(cap);
  }
  while (order.size() > size_t(expected)) {
    const size_t n = order.size();
    nearest_.assign(n, std::numeric_limits<double>::infinity());
    double closest = std::numeric_limits<double>::infinity();
    size_t a = 0, b = 0;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) {
        const double d = (regions_[order[i]].blob.centroid - regions_[order[j]].blob.centroid).norm();
        nearest_[i] = std::min(nearest_[i], d);
        nearest_[j] = std::min(nearest_[j], d);
        if (d < closest) {
          closest = d;
          a = i;
          b = j;
        }
      }
    Region& ra = regions_[order[a]];
    Region& rb = regions_[order[b]];
    if (closest < config_.merge_factor * (ra.blob.radius + rb.blob.radius)) {
      const double background = ra.blob.background;
      ra.sums.merge(rb.sums);
      ra.blob = ra.sums.blob();
      ra.blob.background = background;
      ra.blob.origin = BlobOrigin::kMerged;
      reject(&rb, RejectReason::kMerged, closest);
      order.erase(order.begin() + std::ptrdiff_t(b));
    } else {
      const size_t far = size_t(std::max_element(nearest_.begin(), nearest_.end()) - nearest_.begin());
      reject(&regions_[order[far]], RejectReason::kIsolated, nearest_[far]);
      order.erase(order.begin() + std::ptrdiff_t(far));
    }
  }
}

void WindowPass::split_by_prediction(const Window& w, const std::vector<Eigen::Vector2d>& centres) {
  if (centres.size() < 2) return;
  // Cleared, not assigned anew: each region's list keeps its memory between windows.
  if (held_.size() < regions_.size()) held_.resize(regions_.size());
  for (size_t k = 0; k < regions_.size(); ++k) held_[k].clear();
  const int width = grower_.width();
  for (const Eigen::Vector2d& c : centres) {
    const int x = static_cast<int>(std::lround(c.x())), y = static_cast<int>(std::lround(c.y()));
    if (!w.rect.contains(cv::Point(x, y))) continue;
    const int32_t label = grower_.label(y * width + x);
    if (label == 0) continue;
    for (size_t k = 0; k < regions_.size(); ++k) {
      const Region& r = regions_[k];
      if (r.label != label || r.quiet || !(r.accepted || (r.rejected && !r.recovered && reason_is_shape(r.reason))))
        continue;
      bool distinct = true;  // two ROIs of one marker are one centre
      for (const Eigen::Vector2d& o : held_[k]) distinct = distinct && (o - c).norm() > 1.5;
      if (distinct) held_[k].push_back(c);
    }
  }
  const size_t n = regions_.size();
  for (size_t k = 0; k < n; ++k)
    if (held_[k].size() >= 2) recovery_.split_by_prediction(*w.work, w.rect, w.levels, &grower_, k, held_[k], &regions_);
}

void WindowPass::recover(const Window& w, int missing, const std::vector<BlobRoi>& measured) {
  if (missing <= 0) return;
  if (config_.recover_dim) {
    const size_t first = find(w, w.levels.f2);
    auto& order = order_;
    order.clear();
    for (size_t i = first; i < regions_.size(); ++i) {
      Region& r = regions_[i];
      r.quiet = true;  // dim-pass leftovers are mostly noise: not worth listing
      if (r.accepted) order.push_back(i);
    }
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return regions_[a].blob.intensity > regions_[b].blob.intensity;
    });
    for (size_t k = 0; k < order.size(); ++k) {
      Region& r = regions_[order[k]];
      if (k < size_t(missing)) {
        r.blob.origin = BlobOrigin::kDimRecovery;
        r.quiet = false;
      } else {
        r.accepted = false;
      }
    }
    missing -= static_cast<int>(std::min(order.size(), size_t(missing)));
  }
  if (config_.recover_by_erosion) {
    // Rejected shapes first, then the largest accepted blobs (two markers
    // can merge into a round blob).
    auto& order = order_;
    order.clear();
    const auto measured_there = [&](const Region& r) {
      return std::any_of(measured.begin(), measured.end(),
                         [&](const BlobRoi& roi) { return in_square(r.blob.centroid, roi); });
    };
    for (size_t i = 0; i < regions_.size(); ++i) {
      const Region& r = regions_[i];
      if (!r.accepted && r.rejected && !r.recovered && !r.quiet && reason_is_shape(r.reason) && !measured_there(r))
        order.push_back(i);
    }
    const size_t rejected = order.size();
    for (size_t i = 0; i < regions_.size(); ++i) {
      const Region& r = regions_[i];
      if (r.accepted && r.blob.area >= 2 * config_.min_shape_area && !measured_there(r)) order.push_back(i);
    }
    std::sort(order.begin() + std::ptrdiff_t(rejected), order.end(),
              [&](size_t a, size_t b) { return regions_[a].blob.area > regions_[b].blob.area; });
    for (size_t k = 0; k < order.size() && missing > 0; ++k) {
      const size_t i = order[k];
      const bool was_accepted = regions_[i].accepted;
      const size_t before = regions_.size();
      const int parts = recovery_.split_by_erosion(*w.work, w.rect, w.levels, config_, &grower_, i, &regions_);
      if (parts == 0) continue;
      for (size_t j = before; j < regions_.size(); ++j) regions_[j].blob.background = w.levels.reported_background;
      regions_[i].accepted = false;
      missing -= was_accepted ? parts - 1 : parts;
    }
  }
  if (config_.recover_by_circle_fit) {
    for (size_t i = 0; i < regions_.size() && missing > 0; ++i) {
      Region& r = regions_[i];
      if (r.accepted || !r.rejected || r.recovered || r.quiet) continue;
      if (r.reason != RejectReason::kNonConvex && r.reason != RejectReason::kEccentric) continue;
      if (recovery_.fit_circle(*w.work, w.rect, w.levels, config_, grower_, &r)) --missing;
    }
  }
}

void WindowPass::reject(Region* r, RejectReason reason, double value) {
  r->accepted = false;
  r->rejected = true;
  r->reason = reason;
  r->reason_value = value;
}

void WindowPass::list_rejected(BlobExtraction* out) const {
  for (const Region& r : regions_) {
    if (!r.rejected || r.quiet) continue;
    if (out->rejected.size() >= size_t(std::max(config_.max_rejected_kept, 0))) return;
    RejectedBlob rb;
    rb.centroid = r.blob.centroid;
    rb.bbox = r.blob.bbox;
    rb.area = r.blob.area;
    rb.reason = r.reason;
    rb.value = r.reason_value;
    rb.recovered = r.recovered;
    out->rejected.push_back(rb);
  }
}

void WindowPass::measure(const Window& w, Region* r) {
  grower_.measure(*w.work, w.rect, w.levels, r);
  r->blob.background = w.levels.reported_background;
  classify(config_, r);
  // A blob cut by the image or window border has a biased centroid; its rim is not cut.
  if (r->accepted && ((r->blob.clipped && config_.refit_clipped) ||
                      (config_.fit_every_circle && r->blob.area >= config_.min_shape_area))) {
    recovery_.fit_circle(*w.work, w.rect, w.levels, config_, grower_, r);
  }
}

}  // namespace tetrapulse::blob_internal
