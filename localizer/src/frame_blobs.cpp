#include "frame_blobs.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse::localizer_internal {

int search_burst_frames(const TargetsFile& targets, int64_t frame_period_ns, int64_t exposure_ns) {
  if (targets.modulation.kind == ModulationKind::kConstant || frame_period_ns <= 0) return 1;
  const int64_t T = targets.timebase.bit_period_ns;
  const double frames_per_bit = double(T) / double(frame_period_ns);
  int frames = 1;
  for (const Target& target : targets.targets)
    for (const Marker& marker : target.markers) {
      if (!marker.code) continue;
      const int dark = frames_per_bit < 1.0
                           ? longest_dark_frames(*marker.code, T, frame_period_ns, exposure_ns)
                           : int(std::ceil(longest_zero_run(*marker.code) * frames_per_bit - 1e-9));
      frames = std::max(frames, dark + 1);
    }
  return std::min(frames, 16);
}

FrameBlobs::FrameBlobs(const RigLooks& looks, int full_search_interval)
    : expected_(looks.configs.size(), 0), full_search_interval_(full_search_interval) {
  for (const BlobExtractorConfig& c : looks.configs) extractors_.emplace_back(c);
  for (const auto& of : looks.look_of)
    for (const int l : of) ++expected_[size_t(l)];
}

void FrameBlobs::set_search_burst(int frames) {
  burst_ = frames;
  burst_left_ = frames - 1;  // the first burst began with frame 0
}

tl::expected<void, BlobInputError> FrameBlobs::extract(const cv::Mat& image, const RoiPlan& plan, bool needs_search,
                                                       bool prune_whole) {
  const bool first = frames_++ == 0;
  hits_.clear();
  searched_ = false;
  if (auto r = extract_rois(image, plan); !r) return r;
  patch_absent_rois(plan);
  for (size_t i = 0; i < extraction_.rois.size(); ++i) {
    const RoiMeasurement& m = extraction_.rois[i];
    if (!plan.purposes[i].search || !m.detected()) continue;
    hits_.push_back(SearchHit{extraction_.blobs.size(), *plan.purposes[i].search});
    extraction_.blobs.push_back(m.blob);
  }
  if (!search_now(first, needs_search)) return {};
  if (auto r = extract_whole(image, plan, prune_whole); !r) return r;
  add_whole_image_blobs(plan);
  return {};
}

namespace {

void append_look(const BlobExtraction& part, int look, BlobExtraction* out) {
  for (const Blob& b : part.blobs) {
    out->blobs.push_back(b);
    out->blobs.back().look = look;
  }
  out->rejected.insert(out->rejected.end(), part.rejected.begin(), part.rejected.end());
  out->windows.insert(out->windows.end(), part.windows.begin(), part.windows.end());
}

}  // namespace

void FrameBlobs::gather_look(const RoiPlan& plan, int look) {
  look_rois_.clear();
  look_index_.clear();
  for (size_t i = 0; i < plan.rois.size(); ++i)
    if (plan.purposes[i].look == look) look_rois_.push_back(plan.rois[i]), look_index_.push_back(i);
}

tl::expected<void, BlobInputError> FrameBlobs::extract_rois(const cv::Mat& image, const RoiPlan& plan) {
  if (extractors_.size() == 1) return extractors_[0].extract(image, plan.rois, &extraction_);
  extraction_.clear();
  extraction_.rois.resize(plan.rois.size());
  for (size_t l = 0; l < extractors_.size(); ++l) {
    gather_look(plan, int(l));
    if (look_rois_.empty()) continue;
    if (auto r = extractors_[l].extract(image, look_rois_, &part_); !r) return r;
    for (size_t j = 0; j < look_index_.size(); ++j) {
      extraction_.rois[look_index_[j]] = part_.rois[j];
      extraction_.rois[look_index_[j]].blob.look = int(l);
    }
    append_look(part_, int(l), &extraction_);
  }
  return {};
}

tl::expected<void, BlobInputError> FrameBlobs::extract_whole(const cv::Mat& image, const RoiPlan& plan,
                                                             bool prune_whole) {
  if (extractors_.size() == 1) return extractors_[0].extract(image, expected_[0], &whole_, prune_whole, plan.rois);
  whole_.clear();
  for (size_t l = 0; l < extractors_.size(); ++l) {
    gather_look(plan, int(l));
    if (auto r = extractors_[l].extract(image, expected_[l], &part_, prune_whole, look_rois_); !r) return r;
    append_look(part_, int(l), &whole_);
  }
  return {};
}

namespace {

// A blob outside an exact ROI's square (RoiPurpose::exact) that is far larger than
// its marker's image: another target's marker beside it (a drone hovering 11 px from
// another's marker took its blob in every frame its own was dark, so the other never
// had a track of its own and was not identified again).
bool too_large(const Blob& blob, const RoiPurpose& purpose) {
  constexpr double kRadiusFactor = 1.5, kBlurPx = 1;
  return purpose.exact && blob.radius > kRadiusFactor * purpose.marker_radius_px + kBlurPx;
}

}  // namespace

void FrameBlobs::patch_absent_rois(const RoiPlan& plan) {
  for (size_t i = 0; i < extraction_.rois.size(); ++i) {
    RoiMeasurement& m = extraction_.rois[i];
    if (m.status != RoiStatus::kAbsent) continue;
    const BlobRoi& roi = plan.rois[i];
    int nearest = -1;
    double nearest_d = 2 * roi.radius;
    for (size_t b = 0; b < extraction_.blobs.size(); ++b) {
      if (extraction_.blobs[b].look != plan.purposes[i].look || too_large(extraction_.blobs[b], plan.purposes[i])) continue;
      const double d = (extraction_.blobs[b].centroid - roi.center).norm();
      if (d < nearest_d) nearest_d = d, nearest = int(b);
    }
    if (nearest < 0) continue;
    const Eigen::Vector2d& p = extraction_.blobs[size_t(nearest)].centroid;
    bool closer = false;
    for (size_t j = 0; j < plan.rois.size() && !closer; ++j)
      closer = j != i && plan.purposes[j].look == plan.purposes[i].look &&
               (p - plan.rois[j].center).norm() < nearest_d;
    if (closer) continue;
    m.status = RoiStatus::kDetected;
    m.blob = extraction_.blobs[size_t(nearest)];
    m.position = m.blob.centroid;
    m.intensity = m.blob.intensity;
    extraction_.blobs.erase(extraction_.blobs.begin() + nearest);
  }
}

bool FrameBlobs::search_now(bool first, bool needs_search) {
  if (first || (needs_search && (burst_left_ > 0 || frames_since_search_ + 1 >= full_search_interval_))) {
    if (burst_left_ == 0) burst_left_ = std::max(1, burst_);
    --burst_left_;
    searched_ = true;
    frames_since_search_ = 0;
    return true;
  }
  burst_left_ = 0;
  ++frames_since_search_;
  return false;
}

void FrameBlobs::add_whole_image_blobs(const RoiPlan& plan) {
  const size_t found_in_rois = extraction_.blobs.size();
  for (const Blob& b : whole_.blobs) {
    bool known = false;
    for (size_t i = 0; i < plan.rois.size() && !known; ++i) {
      if (plan.purposes[i].look != b.look) continue;
      const Eigen::Vector2d d = b.centroid - plan.rois[i].center;
      known = std::abs(d.x()) <= plan.rois[i].radius + 1 && std::abs(d.y()) <= plan.rois[i].radius + 1;
    }
    for (size_t i = 0; i < found_in_rois && !known; ++i)
      known = extraction_.blobs[i].look == b.look && (b.centroid - extraction_.blobs[i].centroid).norm() < 3;
    if (!known) extraction_.blobs.push_back(b);
  }
}

}  // namespace tetrapulse::localizer_internal
