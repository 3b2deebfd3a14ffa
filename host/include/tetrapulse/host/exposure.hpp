#pragma once
// Camera exposures in rig time, as the sync master records them, and the file a recorder
// turns into a rig dataset's frames.csv (docs/rig-dataset.md): header
// `frame,timestamp_ns,exposure_ns`, one row per exposure; the sensor integrated light over
// [timestamp_ns, timestamp_ns + exposure_ns) of rig time (integer ns). `frame` counts from
// 0 and skips the numbers of exposures that were missed.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "tetrapulse/host/host_error.hpp"

namespace tetrapulse::host {

struct Exposure {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;  // start of the exposure, rig time
  int64_t exposure_ns = 0;   // its length
};

// Writes the exposures file row by row, each row flushed, so a recorder reading it while
// the sync runs (or after the process was stopped) sees only whole rows.
class ExposureLogWriter {
 public:
  // Creates (truncates) `path` and writes the header; kBadFile when it cannot.
  static HostResult<std::unique_ptr<ExposureLogWriter>> create(const std::string& path);
  ~ExposureLogWriter();
  HostResult<void> write(const Exposure& e);

 private:
  ExposureLogWriter(std::string path, std::FILE* file) : path_(std::move(path)), file_(file) {}
  std::string path_;
  std::FILE* file_;
};

// Turns the edges of a camera's strobe output (active while the sensor integrates) into
// exposures: an active edge starts one, the next inactive edge ends it. With
// `frame_period_ns` > 0 frames are numbered by time from the first exposure (so a missed
// strobe pulse skips a number); with 0 they are counted.
class StrobeEdgePairer {
 public:
  explicit StrobeEdgePairer(int64_t frame_period_ns = 0) : period_ns_(frame_period_ns) {}
  // One edge at rig time `rig_ns`; an exposure when it ends one.
  std::optional<Exposure> edge(bool active, int64_t rig_ns);

 private:
  int64_t period_ns_;
  std::optional<int64_t> start_ns_;
  std::optional<int64_t> first_ns_;
  int64_t count_ = 0;
};

}  // namespace tetrapulse::host
