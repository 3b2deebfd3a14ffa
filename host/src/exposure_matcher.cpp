// ExposureMatcher: frames to exposures as they come (exposure_matcher.hpp).
#include "tetrapulse/host/exposure_matcher.hpp"

#include <cmath>

namespace tetrapulse::host {

void ExposureMatcher::add_exposure(const Exposure& e) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.push_back(e);
}

std::optional<MatchedStamp> ExposureMatcher::match(int64_t arrived_ns, int64_t camera_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!sync_) {
    const int64_t offset = options_.camera_clock_is_rig ? 0 : arrived_ns - (camera_ns + options_.exposure_ns);
    if (!offset_ns_ || offset < *offset_ns_) offset_ns_ = offset;
    if (!first_camera_ns_) first_camera_ns_ = camera_ns;
    int64_t frame = counted_++;
    if (options_.frame_period_ns > 0) {
      frame = static_cast<int64_t>(std::llround(static_cast<double>(camera_ns - *first_camera_ns_) /
                                                static_cast<double>(options_.frame_period_ns)));
      if (last_frame_ && frame <= *last_frame_) frame = *last_frame_ + 1;
    }
    last_frame_ = frame;
    ++counters_.matched;
    return MatchedStamp{Exposure{frame, camera_ns + *offset_ns_, options_.exposure_ns}, !options_.camera_clock_is_rig};
  }
  // The latest exposure that ended at or before the arrival, within max_delay_ns.
  std::optional<size_t> best;
  for (size_t i = 0; i < pending_.size(); ++i) {
    const int64_t end = pending_[i].timestamp_ns + pending_[i].exposure_ns;
    if (end > arrived_ns) break;
    if (arrived_ns - end <= options_.max_delay_ns) best = i;
  }
  if (!best) {
    // Exposures that ended too long ago can no longer be matched.
    while (!pending_.empty() &&
           arrived_ns - (pending_.front().timestamp_ns + pending_.front().exposure_ns) > options_.max_delay_ns) {
      if (last_frame_) ++counters_.dropped;
      else ++counters_.before_first;
      pending_.pop_front();
    }
    ++counters_.unmatched_frames;
    return std::nullopt;
  }
  for (size_t i = 0; i < *best; ++i) {
    if (last_frame_) ++counters_.dropped;
    else ++counters_.before_first;
  }
  Exposure e = pending_[*best];
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(*best) + 1);
  // Frame 0 is the first exposure a frame came from (docs/rig-dataset.md).
  if (!first_sync_frame_) first_sync_frame_ = e.frame;
  e.frame -= *first_sync_frame_;
  last_frame_ = e.frame;
  ++counters_.matched;
  return MatchedStamp{e, false};
}

MatchCounters ExposureMatcher::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

std::optional<int64_t> ExposureMatcher::offset_ns() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return offset_ns_;
}

}  // namespace tetrapulse::host
