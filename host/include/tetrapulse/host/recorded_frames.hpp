#pragma once
// A recorder's last step: from the sync master's exposures (rig time, exposure.hpp) and the
// images the camera delivered to a rig dataset's frames.csv (docs/rig-dataset.md).
//
// Each image comes with the rig time it arrived (the camera driver's buffer timestamp
// through RigClock), which is after its exposure ended (readout, transfer). It belongs to
// the latest exposure that ended at or before it arrived, at most `max_delay_ns` earlier.
// Exposures that no image came from are dropped frames: their numbers are skipped. Frame 0
// is the first exposure an image came from; numbers follow the master's (a missed trigger
// pulse or strobe skips one too).
#include <cstdint>
#include <string>
#include <vector>

#include "tetrapulse/host/exposure.hpp"
#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse::host {

struct CapturedImage {
  std::string file;        // relative to the dataset folder ("frames/000012.png")
  int64_t arrived_ns = 0;  // rig time the host received it
};

struct FrameMatchOptions {
  int64_t max_delay_ns = 50'000'000;  // from the end of an exposure to its image's arrival
};

// Rows of frames.csv, in frame order. kBadInput naming the image when one has no exposure
// within max_delay_ns before it or two images claim one exposure; exposures must be in
// increasing time order.
HostResult<std::vector<FrameRecord>> frames_from_exposures(const std::vector<Exposure>& exposures,
                                                           const std::vector<CapturedImage>& images,
                                                           const FrameMatchOptions& options = {});

// The exposures file ExposureLogWriter writes (`tetrapulse sync --out`); kBadFile naming the
// line of the first problem.
HostResult<std::vector<Exposure>> read_exposures_file(const std::string& path);

// DATASET/frames.csv, written atomically.
HostResult<void> write_frames_csv(const std::string& dataset_dir, const std::vector<FrameRecord>& frames);

}  // namespace tetrapulse::host
