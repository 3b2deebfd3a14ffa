#pragma once
// Internal to Localizer, stage 2 of a frame: the blobs, with the fallbacks a
// tracked scene needs.
//   1. The ROIs of the plan (roi_planner.hpp) through BlobExtractor's ROI mode.
//   2. An ROI that found nothing in its square takes the nearest blob its
//      window found outside any square, within twice its radius, unless another
//      ROI is nearer to that blob: a prediction that missed (a sudden turn)
//      still keeps its track.
//   3. A search ROI's blob becomes a new blob (it starts a track, which the
//      marker it was searched for then claims: search_hits()).
//   4. While something is not tracked, the whole image is searched in bursts of
//      as many consecutive frames as an on-off marker may stay dark (so every
//      lit marker shows in one of them, whatever its code), every
//      full_search_interval frames, and on the first frame. Its blobs that no ROI
//      square of their look holds and no ROI blob of it lies within 3 px of are
//      new blobs too.
// A rig that mixes looks (target_appearance.hpp) has one extractor per look:
// each ROI goes through its look's, the whole image through every one, and each
// blob carries its look.
// Pixels in the OpenCV convention.
#include <cstddef>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <tl/expected.hpp>

#include "roi_planner.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/target_appearance.hpp"

namespace tetrapulse::localizer_internal {

// Consecutive frames a whole-image search lasts: a marker's longest run of 0
// bits in frames, + 1 (for codes whose bits are shorter than a frame, its
// longest run of dark frames from aliasing, + 1), at most 16; 1 under constant
// modulation. A marker in a 0 bit is dark (on_off) or dim (two_level, easily
// below the locating threshold next to bright lamps): some frame of the burst
// sees every marker lit, whatever its code.
int search_burst_frames(const TargetsFile& targets, int64_t frame_period_ns, int64_t exposure_ns);

// A search ROI's blob: extraction().blobs[blob] was looked for as `marker`.
struct SearchHit {
  size_t blob = 0;
  MarkerRef marker;
};

class FrameBlobs {
 public:
  FrameBlobs(const RigLooks& looks, int full_search_interval);

  // Frames a whole-image search lasts (search_burst_frames); known from the second frame on.
  void set_search_burst(int frames);

  // `needs_search`: some target or marker is not tracked. The whole image's
  // blobs of a look are recovered when fewer are found than the rig has markers of
  // it, and pruned to that number when more are found only with `prune_whole` (not
  // for coded markers, whose codes tell clutter apart, and some of which may be dark).
  tl::expected<void, BlobInputError> extract(const cv::Mat& image, const RoiPlan& plan, bool needs_search,
                                             bool prune_whole);

  // The ROIs' measurements (one per plan ROI, in order) and the new blobs.
  const BlobExtraction& extraction() const { return extraction_; }
  // The whole image's blobs, when it was searched this frame.
  const BlobExtraction& whole() const { return whole_; }
  bool searched() const { return searched_; }
  const std::vector<SearchHit>& search_hits() const { return hits_; }

 private:
  // The plan's ROIs of `look` (look_rois_) and their indices in the plan (look_index_).
  void gather_look(const RoiPlan& plan, int look);
  tl::expected<void, BlobInputError> extract_rois(const cv::Mat& image, const RoiPlan& plan);
  tl::expected<void, BlobInputError> extract_whole(const cv::Mat& image, const RoiPlan& plan, bool prune_whole);
  void patch_absent_rois(const RoiPlan& plan);
  bool search_now(bool first, bool needs_search);
  void add_whole_image_blobs(const RoiPlan& plan);

  std::vector<BlobExtractor> extractors_;  // one per look
  std::vector<int> expected_;              // the rig's markers of each look
  int full_search_interval_;
  BlobExtraction extraction_, whole_, part_;
  std::vector<BlobRoi> look_rois_;
  std::vector<size_t> look_index_;
  std::vector<SearchHit> hits_;
  int64_t frames_ = 0;
  int frames_since_search_ = 0;
  int burst_left_ = 0;
  int burst_ = 1;
  bool searched_ = false;
};

}  // namespace tetrapulse::localizer_internal
