#include "tetrapulse/localizer/blob_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "blob_window_pass.hpp"
#include "tetrapulse/localizer/linear_assignment.hpp"

namespace tetrapulse {

using blob_internal::Levels;
using blob_internal::Region;
using blob_internal::Window;

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

// A new frame is in no cache, nor are its pages in the TLB, and the rows of a
// window lie a whole image row apart. Read row after row, a window waits for
// each row in turn (a fifth of ROI extraction on the pipeline benchmark's
// frames); loading a byte of each (64-byte) cache line of every window first
// lets those misses overlap. Prefetch hints alone did not help: a page not yet
// in the TLB seems to void them. Returns the bytes' sum, for the caller to keep.
unsigned touch_rows(const cv::Mat& image, cv::Rect window) {
  const size_t bytes = size_t(window.width) * image.elemSize();
  unsigned sum = 0;
  for (int y = window.y; y < window.y + window.height; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y) + size_t(window.x) * image.elemSize();
    for (size_t b = 0; b < bytes; b += 64) sum += row[b];
    sum += row[bytes - 1];
  }
  return sum;
}

struct Aperture {
  double sum = 0;
  int pixels = 0;
  double peak = 0;
  bool saturated = false;
};

// The columns [*first, *last] of [x0, x1] whose pixel centres lie in the disc:
// (x - cx)^2 + dy2 <= r2, as the aperture's test reads. The test only fails
// more as |x - cx| grows, so they are one run around the column nearest cx (the
// one at or just below cx, or the next); its ends are estimated, then moved
// until the test holds just inside them and fails just outside. False when no
// column is inside.
bool disc_columns(double cx, double dy2, double r2, int x0, int x1, int* first, int* last) {
  const auto inside = [&](int x) { return !((x - cx) * (x - cx) + dy2 > r2); };
  // Clamped to [x0, x1] first, so that truncation rounds down.
  int middle = static_cast<int>(std::clamp(cx, double(x0), double(x1)));
  if (!inside(middle) && !(middle < x1 && inside(++middle))) return false;
  const double half = std::sqrt(std::max(0.0, r2 - dy2));
  int lo = std::min(static_cast<int>(std::clamp(cx - half, double(x0), double(x1))), middle);
  int hi = std::max(static_cast<int>(std::clamp(cx + half, double(x0), double(x1))), middle);
  while (!inside(lo)) ++lo;
  while (lo > x0 && inside(lo - 1)) --lo;
  while (!inside(hi)) --hi;
  while (hi < x1 && inside(hi + 1)) ++hi;
  *first = lo, *last = hi;
  return true;
}

template <typename T>
Aperture measure_aperture_typed(const cv::Mat& work, cv::Rect window, const Levels& levels, const Eigen::Vector2d& c,
                                double radius) {
  Aperture a;
  const cv::Rect box = square_window(c, radius, work.size()) & window;
  const double r2 = radius * radius;
  int top = -1;  // the peak and clipping follow from it (v - background rises with v)
  for (int y = box.y; y < box.y + box.height; ++y) {
    const T* row = work.ptr<T>(y);
    int first = 0, last = -1;
    if (!disc_columns(c.x(), (y - c.y()) * (y - c.y()), r2, box.x, box.x + box.width - 1, &first, &last)) continue;
    for (int x = first; x <= last; ++x) {
      a.sum += double(row[x]) - levels.background;
      top = std::max(top, int(row[x]));
    }
    a.pixels += last - first + 1;
  }
  if (a.pixels == 0) return a;
  a.peak = double(top) - levels.background;
  a.saturated = top >= levels.saturation;
  return a;
}

Aperture measure_aperture(const cv::Mat& work, cv::Rect window, const Levels& levels, const Eigen::Vector2d& c,
                          double radius) {
  return work.depth() == CV_8U ? measure_aperture_typed<uint8_t>(work, window, levels, c, radius)
                               : measure_aperture_typed<uint16_t>(work, window, levels, c, radius);
}

}  // namespace

namespace blob_internal {

// Scratch memory kept between calls, and the ROI mode's own steps.
class ExtractorScratch {
 public:
  explicit ExtractorScratch(const BlobExtractorConfig& config) : pass(config) {}

  // Windows of the ROIs (empty when outside the image), gathered into groups
  // whose windows overlap, grown until the groups' windows are disjoint.
  void group_windows(const std::vector<BlobRoi>& rois, cv::Size size) {
    roi_windows.resize(rois.size());
    for (size_t i = 0; i < rois.size(); ++i) {
      const double half = std::max(rois[i].radius, 0.0) + std::max(rois[i].aperture_radius, 0.0);
      roi_windows[i] = square_window(rois[i].center, half, size);
    }
    group_of.assign(rois.size(), -1);
    groups.clear();
    for (size_t i = 0; i < rois.size(); ++i) {
      if (roi_windows[i].empty()) continue;
      group_of[i] = static_cast<int>(groups.size());
      groups.push_back(roi_windows[i]);
    }
    // Overlapping windows join (union-find, a component's root its first window),
    // then the joined windows are checked again, until none overlap (merging one
    // pair a scan was O(G^3) when the ROIs of 32 targets overlap). Pairs are found
    // by a sweep over the windows sorted by left edge, so that a window is compared
    // only with those that start before it ends (all pairs were 8128 tests a round
    // for 32 targets' 128 ROIs). The groups keep the order of their first ROI.
    for (bool joined = true; joined;) {
      joined = false;
      const size_t g = groups.size();
      parent.resize(g);
      for (size_t i = 0; i < g; ++i) parent[i] = int(i);
      const auto root = [&](int i) {
        while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        return i;
      };
      by_left.resize(g);
      for (size_t i = 0; i < g; ++i) by_left[i] = int(i);
      std::sort(by_left.begin(), by_left.end(), [&](int a, int b) { return groups[size_t(a)].x < groups[size_t(b)].x; });
      for (size_t p = 0; p < g; ++p) {
        const cv::Rect& a = groups[size_t(by_left[p])];
        for (size_t q = p + 1; q < g && groups[size_t(by_left[q])].x < a.x + a.width; ++q) {
          const cv::Rect& b = groups[size_t(by_left[q])];
          if (b.y >= a.y + a.height || a.y >= b.y + b.height) continue;
          const int ra = root(by_left[p]), rb = root(by_left[q]);
          if (ra == rb) continue;
          parent[size_t(std::max(ra, rb))] = std::min(ra, rb);
          joined = true;
        }
      }
      if (!joined) break;
      renumber.assign(g, -1);
      size_t kept = 0;
      for (size_t i = 0; i < g; ++i) {
        const int r = root(int(i));
        if (r == int(i)) {
          renumber[i] = int(kept);
          groups[kept++] = groups[i];
        } else {
          groups[size_t(renumber[size_t(r)])] |= groups[i];
        }
      }
      for (size_t i = 0; i < g; ++i) renumber[i] = renumber[size_t(root(int(i)))];
      groups.resize(kept);
      for (int& gi : group_of)
        if (gi >= 0) gi = renumber[size_t(gi)];
    }
    // Each group's ROIs in ROI order, listed once (a scan of every ROI for each group
    // was G x R: 16 000 tests a frame for 32 targets).
    member_begin.assign(groups.size() + 1, 0);
    for (const int gi : group_of)
      if (gi >= 0) ++member_begin[size_t(gi) + 1];
    for (size_t g = 0; g < groups.size(); ++g) member_begin[g + 1] += member_begin[g];
    member_list.resize(size_t(member_begin.back()));
    fill.assign(member_begin.begin(), member_begin.end() - 1);
    for (size_t i = 0; i < rois.size(); ++i)
      if (group_of[i] >= 0) member_list[size_t(fill[size_t(group_of[i])]++)] = static_cast<int>(i);
  }

  // The ROIs of group `g` become `members`.
  void take_members(size_t g) {
    members.assign(member_list.begin() + member_begin[g], member_list.begin() + member_begin[g + 1]);
  }

  // Accepted blobs whose centroid lies in the square of a ROI of `members`.
  int claimed(const std::vector<BlobRoi>& rois) {
    int count = 0;
    for (const Region& r : pass.regions()) {
      if (!r.accepted) continue;
      count += std::any_of(members.begin(), members.end(),
                           [&](int i) { return in_square(r.blob.centroid, rois[size_t(i)]); });
    }
    return count;
  }

  // The group's ROIs take its blobs by a globally optimal assignment (least
  // squared distance, centroid inside the ROI's square); each ROI's
  // measurement is filled, and the blobs no ROI took go to out->blobs.
  void answer(const std::vector<BlobRoi>& rois, const Window& w, BlobExtraction* out) {
    std::vector<Region>& regions = pass.regions();
    group_blobs.clear();
    for (size_t k = 0; k < regions.size(); ++k)
      if (regions[k].accepted) group_blobs.push_back(k);
    const int rows = static_cast<int>(members.size()), cols = static_cast<int>(group_blobs.size());
    cost.assign(size_t(rows) * cols, LinearAssignment::kForbidden);
    for (int r = 0; r < rows; ++r) {
      const BlobRoi& roi = rois[size_t(members[size_t(r)])];
      for (int c = 0; c < cols; ++c) {
        const Eigen::Vector2d& p = regions[group_blobs[size_t(c)]].blob.centroid;
        if (in_square(p, roi)) cost[size_t(r) * cols + c] = (p - roi.center).squaredNorm();
      }
    }
    assignment.solve(cost.data(), rows, cols, &assigned);
    for (int r = 0; r < rows; ++r) {
      const int i = members[size_t(r)];
      RoiMeasurement& m = out->rois[size_t(i)];
      m.background = w.levels.reported_background;
      m.background_sigma = w.levels.sigma;
      const int c = assigned[size_t(r)];
      if (c >= 0) {
        Region& region = regions[group_blobs[size_t(c)]];
        m.status = RoiStatus::kDetected;
        m.blob = region.blob;
        m.position = region.blob.centroid;
        m.intensity = region.blob.intensity;
        region.accepted = false;  // taken: not an unassigned blob
      } else {
        m.status = RoiStatus::kAbsent;
      }
      const Aperture a =
          measure_aperture(*w.work, w.rect, w.levels, m.position, std::max(rois[size_t(i)].aperture_radius, 0.0));
      m.aperture_intensity = a.sum;
      m.aperture_pixels = a.pixels;
      m.aperture_peak = a.peak;
      m.aperture_saturated = a.saturated;
      if (c < 0) m.intensity = a.sum;
    }
    for (const Region& r : regions)
      if (r.accepted) out->blobs.push_back(r.blob);
  }

  WindowPass pass;
  LinearAssignment assignment;
  std::vector<double> cost;
  std::vector<int> assigned;
  std::vector<cv::Rect> roi_windows;
  std::vector<int> group_of;  // group of each ROI; -1: outside the image
  std::vector<cv::Rect> groups;
  std::vector<int> parent, renumber, by_left;  // group_windows' union-find and sweep
  std::vector<int> member_list, member_begin, fill;  // ROIs by group: group g's from member_begin[g]
  std::vector<int> members;                          // ROIs of the group being processed
  std::vector<size_t> group_blobs;
  std::vector<Eigen::Vector2d> centres;  // of the group's ROIs that split merged blobs
  unsigned touched = 0;  // touch_rows' sums, kept so that its loads are not left out
};

}  // namespace blob_internal

BlobExtractor::BlobExtractor(BlobExtractorConfig config)
    : config_(config), scratch_(std::make_unique<blob_internal::ExtractorScratch>(config_)) {}
BlobExtractor::~BlobExtractor() = default;
BlobExtractor::BlobExtractor(BlobExtractor&&) noexcept = default;
BlobExtractor& BlobExtractor::operator=(BlobExtractor&&) noexcept = default;

tl::expected<void, BlobInputError> BlobExtractor::extract(const cv::Mat& image, int expected, BlobExtraction* out,
                                                          bool prune, const std::vector<BlobRoi>& measured) {
  out->clear();
  if (auto ok = check_image(image, config_); !ok) return ok;
  blob_internal::WindowPass& pass = scratch_->pass;
  pass.begin(image.size());
  const Window w = pass.prepare(image, cv::Rect(0, 0, image.cols, image.rows), out, /*flatten=*/true);
  pass.find(w, w.levels.f1);
  if (expected > 0) {
    const int found = pass.accepted();
    if (found < expected) pass.recover(w, expected - found, measured);
    // A split can find more markers than were missing.
    if (prune && pass.accepted() > expected) pass.prune(expected);
  }
  for (const Region& r : pass.regions())
    if (r.accepted) out->blobs.push_back(r.blob);
  std::sort(out->blobs.begin(), out->blobs.end(), [](const Blob& a, const Blob& b) {
    return a.centroid.y() < b.centroid.y() || (a.centroid.y() == b.centroid.y() && a.centroid.x() < b.centroid.x());
  });
  pass.list_rejected(out);
  pass.finish();
  return {};
}

tl::expected<void, BlobInputError> BlobExtractor::extract(const cv::Mat& image, const std::vector<BlobRoi>& rois,
                                                          BlobExtraction* out) {
  out->clear();
  if (auto ok = check_image(image, config_); !ok) return ok;
  blob_internal::ExtractorScratch& s = *scratch_;
  blob_internal::WindowPass& pass = s.pass;
  pass.begin(image.size());
  out->rois.resize(rois.size());
  for (size_t i = 0; i < rois.size(); ++i) {
    RoiMeasurement& m = out->rois[i];
    m = RoiMeasurement{};
    m.tag = rois[i].tag;
    m.position = rois[i].center;
  }
  s.group_windows(rois, image.size());
  for (const cv::Rect& g : s.groups) s.touched += touch_rows(image, g);
  for (size_t g = 0; g < s.groups.size(); ++g) {
    pass.next_window();
    s.take_members(g);
    const Window w = pass.prepare(image, s.groups[g], out);
    pass.find(w, w.levels.f1);
    // Predictions split merged markers before any recovery guesses at them.
    s.centres.clear();
    for (int i : s.members)
      if (rois[size_t(i)].splits) s.centres.push_back(rois[size_t(i)].center);
    pass.split_by_prediction(w, s.centres);
    const int found = s.claimed(rois);
    if (found < int(s.members.size())) pass.recover(w, int(s.members.size()) - found);
    s.answer(rois, w, out);
    pass.list_rejected(out);
  }
  pass.finish();
  return {};
}

}  // namespace tetrapulse
