#pragma once
// Live matching of camera frames to their exposures in rig time (integer ns).
//
// With a sync master in the same process (GpioSync trigger or strobe, exposure.hpp),
// exposures come from its thread through add_exposure() and frames from the capture
// loop through match(): a frame belongs to the latest exposure that ended at or before
// it arrived, at most max_delay_ns earlier (readout + transfer), and not claimed
// already. Exposures passed over are frames the camera dropped; exposures before the
// first frame (a late first frame) are discarded; a frame with no such exposure is a
// mismatch and is not stamped. Every case is counted.
//
// Without sync wiring the camera's own timestamps are mapped onto rig time:
// rig = camera_ns + offset, the offset estimated as the smallest
// arrived - (camera_ns + exposure_ns) seen so far (the fastest transfer), so a stamp
// is early by the camera's shortest readout+transfer at most. Poses made so carry
// `estimated` (the stamp is not from the sync master).
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

#include "tetrapulse/host/exposure.hpp"

namespace tetrapulse::host {

struct MatchCounters {
  uint64_t matched = 0;
  uint64_t dropped = 0;          // exposures no frame came from (after the first match)
  uint64_t before_first = 0;     // exposures before the first frame arrived
  uint64_t unmatched_frames = 0; // frames with no exposure within max_delay_ns
};

struct MatchedStamp {
  Exposure exposure;       // frame number, start, length (rig time)
  bool estimated = false;  // from the camera clock and an estimated offset, not the sync master
};

class ExposureMatcher {
 public:
  struct Options {
    int64_t max_delay_ns = 50'000'000;   // exposure end -> frame arrival
    int64_t exposure_ns = 2'000'000;     // for camera-clock mode: the exposure set
    int64_t frame_period_ns = 0;         // camera-clock mode: > 0 numbers frames by time
    // Camera-clock mode: the camera's clock already is rig time (IEEE 1588 PTP with the
    // sync master, or a simulated camera): offset 0, stamps not estimated.
    bool camera_clock_is_rig = false;
  };
  // sync: exposures will come from add_exposure(); else the camera clock is used.
  ExposureMatcher(bool sync, Options options) : sync_(sync), options_(options) {}

  // From the sync master's thread.
  void add_exposure(const Exposure& e);
  // A frame that arrived at rig time arrived_ns with camera timestamp camera_ns
  // (camera clock, exposure start; 0: none). nullopt: a mismatch (counted).
  std::optional<MatchedStamp> match(int64_t arrived_ns, int64_t camera_ns);

  MatchCounters counters() const;
  bool synchronised() const { return sync_; }
  // Camera-clock mode: the current offset estimate (rig - camera), if any frame came.
  std::optional<int64_t> offset_ns() const;

 private:
  bool sync_;
  Options options_;
  mutable std::mutex mutex_;
  std::deque<Exposure> pending_;
  std::optional<int64_t> last_frame_;
  std::optional<int64_t> offset_ns_;
  std::optional<int64_t> first_camera_ns_;
  std::optional<int64_t> first_sync_frame_;
  int64_t counted_ = 0;
  MatchCounters counters_;
};

}  // namespace tetrapulse::host
