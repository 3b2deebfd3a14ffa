#include "tetrapulse/localizer/blob_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "background_histogram.hpp"
#include "blob_recovery.hpp"
#include "blob_regions.hpp"
#include "blob_working_image.hpp"
#include "tetrapulse/localizer/linear_assignment.hpp"

namespace tetrapulse {

using blob_internal::Levels;
using blob_internal::Region;

namespace {

tl::unexpected<BlobInputError> input_error(std::string message) {
  return tl::unexpected<BlobInputError>(BlobInputError{std::move(message)});
}

tl::expected<void, BlobInputError> check_image(const cv::Mat& image, const BlobExtractorConfig& config) {
  if (image.empty()) return input_error("image: empty");
  if (image.dims != 2) return input_error(fmt::format("image: {} dimensions, expected 2", image.dims));
  if (int64_t(image.rows) * image.cols > (int64_t(1) << 30)) {
    return input_error(fmt::format("image: {}x{} pixels is too large", image.cols, image.rows));
  }
  const int type = image.type();
  if (config.colour && type != CV_8UC3) {
    return input_error("image: a colour target needs an 8-bit BGR image");
  }
  if (type != CV_8UC1 && type != CV_16UC1 && type != CV_8UC3) {
    return input_error(fmt::format("image: type {} is not supported (8- or 16-bit grey, or 8-bit BGR)",
                                   cv::typeToString(type)));
  }
  return {};
}

// Pixels whose centres lie in [c - half, c + half] on both axes, inside the image.
cv::Rect square_window(const Eigen::Vector2d& c, double half, cv::Size size) {
  if (!c.allFinite() || !std::isfinite(half) || half < 0) return {};
  const auto clamp = [](double v, int lo, int hi) { return static_cast<int>(std::clamp(v, double(lo), double(hi))); };
  const int x0 = clamp(std::ceil(c.x() - half), 0, size.width), x1 = clamp(std::floor(c.x() + half), -1, size.width - 1);
  const int y0 = clamp(std::ceil(c.y() - half), 0, size.height), y1 = clamp(std::floor(c.y() + half), -1, size.height - 1);
  if (x1 < x0 || y1 < y0) return {};
  return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
}

bool in_square(const Eigen::Vector2d& p, const BlobRoi& roi) {
  return std::abs(p.x() - roi.center.x()) <= roi.radius && std::abs(p.y() - roi.center.y()) <= roi.radius;
}

struct Aperture {
  double sum = 0;
  int pixels = 0;
  double peak = 0;
  bool saturated = false;
};

template <typename T>
Aperture measure_aperture_typed(const cv::Mat& work, cv::Rect window, const Levels& levels, const Eigen::Vector2d& c,
                                double radius) {
  Aperture a;
  const cv::Rect box = square_window(c, radius, work.size()) & window;
  const double r2 = radius * radius;
  a.peak = -std::numeric_limits<double>::infinity();
  for (int y = box.y; y < box.y + box.height; ++y) {
    const T* row = work.ptr<T>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if ((x - c.x()) * (x - c.x()) + (y - c.y()) * (y - c.y()) > r2) continue;
      const double v = row[x];
      a.sum += v - levels.background;
      ++a.pixels;
      a.peak = std::max(a.peak, v - levels.background);
      a.saturated = a.saturated || v >= levels.saturation;
    }
  }
  if (a.pixels == 0) a.peak = 0;
  return a;
}

Aperture measure_aperture(const cv::Mat& work, cv::Rect window, const Levels& levels, const Eigen::Vector2d& c,
                          double radius) {
  return work.depth() == CV_8U ? measure_aperture_typed<uint8_t>(work, window, levels, c, radius)
                               : measure_aperture_typed<uint16_t>(work, window, levels, c, radius);
}

bool reason_is_shape(RejectReason r) {
  return r == RejectReason::kNonConvex || r == RejectReason::kEccentric || r == RejectReason::kTooLarge;
}

}  // namespace

namespace blob_internal {

// Scratch memory kept between calls.
class ExtractorScratch {
 public:
  blob_internal::WorkingImage working;
  blob_internal::BackgroundHistogram histogram;
  blob_internal::RegionGrower grower;
  blob_internal::BlobRecovery recovery;
  std::vector<Region> regions;
  std::vector<size_t> order;
  std::vector<double> nearest;
  LinearAssignment assignment;
  std::vector<double> cost;
  std::vector<int> assigned;
  // ROI mode
  std::vector<cv::Rect> roi_windows;
  std::vector<int> group_of;
  std::vector<cv::Rect> groups;
  std::vector<int> members;
  std::vector<size_t> group_blobs;
};

}  // namespace blob_internal

BlobExtractor::BlobExtractor(BlobExtractorConfig config)
    : config_(config), scratch_(std::make_unique<blob_internal::ExtractorScratch>()) {}
BlobExtractor::~BlobExtractor() = default;
BlobExtractor::BlobExtractor(BlobExtractor&&) noexcept = default;
BlobExtractor& BlobExtractor::operator=(BlobExtractor&&) noexcept = default;

namespace {

// Everything one window needs: its working image and levels.
struct Window {
  cv::Rect rect;
  const cv::Mat* work = nullptr;
  Levels levels;
};

double type_max(const cv::Mat& image) { return image.depth() == CV_16U ? 65535.0 : 255.0; }

// The input's grey level for a working level (dark markers are inverted).
double to_input(double level, const cv::Mat& image, const BlobExtractorConfig& config) {
  const bool inverted = config.polarity == MarkerPolarity::kDark && !config.colour;
  return inverted ? type_max(image) - level : level;
}

}  // namespace

namespace blob_internal {

// The steps shared by both modes, over one window.
class WindowPass {
 public:
  WindowPass(const BlobExtractorConfig& config, ExtractorScratch* scratch) : config_(config), s_(*scratch) {}

  Window prepare(const cv::Mat& image, cv::Rect rect, BlobExtraction* out) {
    Window w;
    w.rect = rect;
    w.work = &s_.working.prepare(image, rect, config_.polarity, config_.colour);
    s_.histogram.count(*w.work, rect);
    const BackgroundFit fit = s_.histogram.fit_background();
    Levels& lv = w.levels;
    lv.background = fit.mean;
    lv.sigma = std::max({fit.sigma, config_.min_background_sigma, 0.5 * s_.histogram.bin_width()});
    lv.f2 = lv.background + config_.f2_sigmas * lv.sigma;
    lv.f1 = std::max({s_.histogram.otsu(), lv.background + config_.f1_min_sigmas * lv.sigma, lv.f2});
    const bool inverted = config_.polarity == MarkerPolarity::kDark && !config_.colour;
    const double top = image.channels() == 3 ? 255.0 : type_max(image);
    lv.saturation = inverted || config_.saturation_level <= 0 ? top : config_.saturation_level;
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

  // Grows, measures and tests the regions seeded above `seed_level`; returns the index of the first new one.
  size_t find(const Window& w, double seed_level) {
    const size_t first = s_.regions.size();
    s_.grower.grow(*w.work, w.rect, w.levels, seed_level, &s_.regions);
    for (size_t i = first; i < s_.regions.size(); ++i) measure(w, &s_.regions[i]);
    return first;
  }

  int accepted() const {
    return static_cast<int>(
        std::count_if(s_.regions.begin(), s_.regions.end(), [](const Region& r) { return r.accepted; }));
  }

  // More blobs than expected: merge touching pairs, drop isolated ones.
  void prune(int expected) {
    auto& order = s_.order;
    order.clear();
    for (size_t i = 0; i < s_.regions.size(); ++i)
      if (s_.regions[i].accepted) order.push_back(i);
    // Far too many (clutter): keep the brightest few before the quadratic pruning.
    const size_t cap = size_t(4 * expected + 32);
    if (order.size() > cap) {
      std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return s_.regions[a].blob.intensity > s_.regions[b].blob.intensity;
      });
      for (size_t k = cap; k < order.size(); ++k) reject(&s_.regions[order[k]], RejectReason::kFaint,
                                                          s_.regions[order[k]].blob.intensity);
      order.resize(cap);
    }
    while (order.size() > size_t(expected)) {
      const size_t n = order.size();
      s_.nearest.assign(n, std::numeric_limits<double>::infinity());
      double closest = std::numeric_limits<double>::infinity();
      size_t a = 0, b = 0;
      for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
          const double d = (s_.regions[order[i]].blob.centroid - s_.regions[order[j]].blob.centroid).norm();
          s_.nearest[i] = std::min(s_.nearest[i], d);
          s_.nearest[j] = std::min(s_.nearest[j], d);
          if (d < closest) {
            closest = d;
            a = i;
            b = j;
          }
        }
      Region& ra = s_.regions[order[a]];
      Region& rb = s_.regions[order[b]];
      if (closest < config_.merge_factor * (ra.blob.radius + rb.blob.radius)) {
        const double background = ra.blob.background;
        ra.sums.merge(rb.sums);
        ra.blob = ra.sums.blob();
        ra.blob.background = background;
        ra.blob.origin = BlobOrigin::kMerged;
        reject(&rb, RejectReason::kMerged, closest);
        order.erase(order.begin() + std::ptrdiff_t(b));
      } else {
        const size_t far = size_t(std::max_element(s_.nearest.begin(), s_.nearest.end()) - s_.nearest.begin());
        reject(&s_.regions[order[far]], RejectReason::kIsolated, s_.nearest[far]);
        order.erase(order.begin() + std::ptrdiff_t(far));
      }
    }
  }

  // Fewer blobs than expected: the cascade, cheapest first; stops once `missing` are found.
  void recover(const Window& w, int missing) {
    if (missing <= 0) return;
    if (config_.recover_dim) {
      const size_t first = find(w, w.levels.f2);
      auto& order = s_.order;
      order.clear();
      for (size_t i = first; i < s_.regions.size(); ++i) {
        Region& r = s_.regions[i];
        r.quiet = true;  // dim-pass leftovers are mostly noise: not worth listing
        if (r.accepted) order.push_back(i);
      }
      std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return s_.regions[a].blob.intensity > s_.regions[b].blob.intensity;
      });
      for (size_t k = 0; k < order.size(); ++k) {
        Region& r = s_.regions[order[k]];
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
      auto& order = s_.order;
      order.clear();
      for (size_t i = 0; i < s_.regions.size(); ++i) {
        const Region& r = s_.regions[i];
        if (!r.accepted && r.rejected && !r.recovered && !r.quiet && reason_is_shape(r.reason)) order.push_back(i);
      }
      const size_t rejected = order.size();
      for (size_t i = 0; i < s_.regions.size(); ++i) {
        const Region& r = s_.regions[i];
        if (r.accepted && r.blob.area >= 2 * config_.min_shape_area) order.push_back(i);
      }
      std::sort(order.begin() + std::ptrdiff_t(rejected), order.end(),
                [&](size_t a, size_t b) { return s_.regions[a].blob.area > s_.regions[b].blob.area; });
      for (size_t k = 0; k < order.size() && missing > 0; ++k) {
        const size_t i = order[k];
        const bool was_accepted = s_.regions[i].accepted;
        const size_t before = s_.regions.size();
        const int parts = s_.recovery.split_by_erosion(*w.work, w.rect, w.levels, config_, &s_.grower, i, &s_.regions);
        if (parts == 0) continue;
        for (size_t j = before; j < s_.regions.size(); ++j) s_.regions[j].blob.background = w.levels.reported_background;
        s_.regions[i].accepted = false;
        missing -= was_accepted ? parts - 1 : parts;
      }
    }
    if (config_.recover_by_circle_fit) {
      for (size_t i = 0; i < s_.regions.size() && missing > 0; ++i) {
        Region& r = s_.regions[i];
        if (r.accepted || !r.rejected || r.recovered || r.quiet) continue;
        if (r.reason != RejectReason::kNonConvex && r.reason != RejectReason::kEccentric) continue;
        if (s_.recovery.fit_circle(*w.work, w.rect, w.levels, config_, s_.grower, &r)) --missing;
      }
    }
  }

  void reject(Region* r, RejectReason reason, double value) {
    r->accepted = false;
    r->rejected = true;
    r->reason = reason;
    r->reason_value = value;
  }

  void list_rejected(BlobExtraction* out) {
    for (const Region& r : s_.regions) {
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

 private:
  void measure(const Window& w, Region* r) {
    s_.grower.measure(*w.work, w.rect, w.levels, r);
    r->blob.background = w.levels.reported_background;
    blob_internal::classify(config_, r);
    // A blob cut by the image or window border has a biased centroid; its rim is not cut.
    if (r->accepted && r->blob.clipped && config_.refit_clipped) {
      s_.recovery.fit_circle(*w.work, w.rect, w.levels, config_, s_.grower, r);
    }
  }

  const BlobExtractorConfig& config_;
  ExtractorScratch& s_;
};

}  // namespace blob_internal

tl::expected<void, BlobInputError> BlobExtractor::extract(const cv::Mat& image, int expected, BlobExtraction* out) {
  out->clear();
  if (auto ok = check_image(image, config_); !ok) return ok;
  blob_internal::ExtractorScratch& s = *scratch_;
  s.grower.reset(image.size());
  s.regions.clear();
  blob_internal::WindowPass pass(config_, &s);
  const Window w = pass.prepare(image, cv::Rect(0, 0, image.cols, image.rows), out);
  pass.find(w, w.levels.f1);
  if (expected > 0) {
    const int found = pass.accepted();
    if (found < expected) pass.recover(w, expected - found);
    // A split can find more markers than were missing.
    if (pass.accepted() > expected) pass.prune(expected);
  }
  for (const Region& r : s.regions)
    if (r.accepted) out->blobs.push_back(r.blob);
  std::sort(out->blobs.begin(), out->blobs.end(), [](const Blob& a, const Blob& b) {
    return a.centroid.y() < b.centroid.y() || (a.centroid.y() == b.centroid.y() && a.centroid.x() < b.centroid.x());
  });
  pass.list_rejected(out);
  s.grower.clear();
  return {};
}

tl::expected<void, BlobInputError> BlobExtractor::extract(const cv::Mat& image, const std::vector<BlobRoi>& rois,
                                                          BlobExtraction* out) {
  out->clear();
  if (auto ok = check_image(image, config_); !ok) return ok;
  blob_internal::ExtractorScratch& s = *scratch_;
  s.grower.reset(image.size());
  const int n = static_cast<int>(rois.size());
  out->rois.resize(rois.size());
  s.roi_windows.resize(rois.size());
  for (int i = 0; i < n; ++i) {
    const BlobRoi& roi = rois[size_t(i)];
    RoiMeasurement& m = out->rois[size_t(i)];
    m = RoiMeasurement{};
    m.tag = roi.tag;
    m.position = roi.center;
    const double half = std::max(roi.radius, 0.0) + std::max(roi.aperture_radius, 0.0);
    s.roi_windows[size_t(i)] = square_window(roi.center, half, image.size());
  }

  // Groups of ROIs whose windows overlap, grown until the groups' windows are disjoint.
  s.group_of.assign(rois.size(), -1);
  s.groups.clear();
  for (int i = 0; i < n; ++i) {
    if (s.roi_windows[size_t(i)].empty()) continue;
    s.group_of[size_t(i)] = static_cast<int>(s.groups.size());
    s.groups.push_back(s.roi_windows[size_t(i)]);
  }
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t a = 0; a < s.groups.size() && !merged; ++a)
      for (size_t b = a + 1; b < s.groups.size() && !merged; ++b) {
        if ((s.groups[a] & s.groups[b]).empty()) continue;
        s.groups[a] |= s.groups[b];
        s.groups.erase(s.groups.begin() + std::ptrdiff_t(b));
        for (int& g : s.group_of) {
          if (g == int(b)) g = int(a);
          else if (g > int(b)) --g;
        }
        merged = true;
      }
  }

  blob_internal::WindowPass pass(config_, &s);
  for (size_t g = 0; g < s.groups.size(); ++g) {
    s.regions.clear();
    const Window w = pass.prepare(image, s.groups[g], out);
    s.members.clear();
    for (int i = 0; i < n; ++i)
      if (s.group_of[size_t(i)] == int(g)) s.members.push_back(i);
    pass.find(w, w.levels.f1);
    const auto claimed = [&] {
      int count = 0;
      for (const Region& r : s.regions) {
        if (!r.accepted) continue;
        count += std::any_of(s.members.begin(), s.members.end(),
                             [&](int i) { return in_square(r.blob.centroid, rois[size_t(i)]); });
      }
      return count;
    };
    const int found = claimed();
    if (found < int(s.members.size())) pass.recover(w, int(s.members.size()) - found);

    // Globally optimal ROI <- blob assignment: least squared distance, inside the ROI's square.
    s.group_blobs.clear();
    for (size_t k = 0; k < s.regions.size(); ++k)
      if (s.regions[k].accepted) s.group_blobs.push_back(k);
    const int rows = static_cast<int>(s.members.size()), cols = static_cast<int>(s.group_blobs.size());
    s.cost.assign(size_t(rows) * cols, LinearAssignment::kForbidden);
    for (int r = 0; r < rows; ++r) {
      const BlobRoi& roi = rois[size_t(s.members[size_t(r)])];
      for (int c = 0; c < cols; ++c) {
        const Eigen::Vector2d& p = s.regions[s.group_blobs[size_t(c)]].blob.centroid;
        if (in_square(p, roi)) s.cost[size_t(r) * cols + c] = (p - roi.center).squaredNorm();
      }
    }
    s.assignment.solve(s.cost.data(), rows, cols, &s.assigned);
    for (int r = 0; r < rows; ++r) {
      const int i = s.members[size_t(r)];
      const BlobRoi& roi = rois[size_t(i)];
      RoiMeasurement& m = out->rois[size_t(i)];
      m.background = w.levels.reported_background;
      m.background_sigma = w.levels.sigma;
      const int c = s.assigned[size_t(r)];
      if (c >= 0) {
        Region& region = s.regions[s.group_blobs[size_t(c)]];
        m.status = RoiStatus::kDetected;
        m.blob = region.blob;
        m.position = region.blob.centroid;
        m.intensity = region.blob.intensity;
        region.accepted = false;  // taken: not an unassigned blob
      } else {
        m.status = RoiStatus::kAbsent;
      }
      const Aperture a = measure_aperture(*w.work, w.rect, w.levels, m.position, std::max(roi.aperture_radius, 0.0));
      m.aperture_intensity = a.sum;
      m.aperture_pixels = a.pixels;
      m.aperture_peak = a.peak;
      m.aperture_saturated = a.saturated;
      if (c < 0) m.intensity = a.sum;
    }
    for (const Region& r : s.regions)
      if (r.accepted) out->blobs.push_back(r.blob);
    pass.list_rejected(out);
  }
  s.grower.clear();
  return {};
}

const char* blob_origin_name(BlobOrigin origin) {
  switch (origin) {
    case BlobOrigin::kThreshold: return "threshold";
    case BlobOrigin::kDimRecovery: return "dim_recovery";
    case BlobOrigin::kErosionSplit: return "erosion_split";
    case BlobOrigin::kCircleFit: return "circle_fit";
    case BlobOrigin::kMerged: return "merged";
  }
  return "?";
}

const char* reject_reason_name(RejectReason reason) {
  switch (reason) {
    case RejectReason::kTooSmall: return "too_small";
    case RejectReason::kTooLarge: return "too_large";
    case RejectReason::kNonConvex: return "non_convex";
    case RejectReason::kEccentric: return "eccentric";
    case RejectReason::kIsolated: return "isolated";
    case RejectReason::kMerged: return "merged";
    case RejectReason::kFaint: return "faint";
  }
  return "?";
}

const char* roi_status_name(RoiStatus status) {
  switch (status) {
    case RoiStatus::kDetected: return "detected";
    case RoiStatus::kAbsent: return "absent";
    case RoiStatus::kOutsideImage: return "outside_image";
  }
  return "?";
}

}  // namespace tetrapulse
