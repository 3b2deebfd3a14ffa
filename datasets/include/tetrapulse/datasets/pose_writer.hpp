#pragma once
// Writing the localizer's poses:
//   csv    poses.csv exactly as docs/rig-dataset.md defines it;
//   tum    TUM RGB-D trajectories, "timestamp tx ty tz qx qy qz qw" with the
//          mid-exposure time in seconds: one file per target (PATH itself for a
//          single target, else STEM.target<ID>EXT);
//   jsonl  one JSON object per pose: frame, timestamp_ns, target, status,
//          markers, reprojection_px, t [m], q [x, y, z, w], and covariance: the
//          6x6 covariance of (w, v) row-major (rad, m; R <- exp([w]x) R,
//          t <- t + v, camera frame; pose_refinement.hpp), or null.
// Poses are written in place as they come, a frame at a time: write() keeps a
// frame's lines, flush() hands them to the file in one write and flushes it. A
// run that fails, is stopped (SIGINT) or killed therefore leaves every frame
// flushed so far, in whole rows, and never half a row. "-" is standard output.
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "tetrapulse/datasets/dataset_error.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace tetrapulse {

enum class PoseFormat { kCsv, kTum, kJsonLines };
const char* pose_format_name(PoseFormat format);

class PoseWriter {
 public:
  static DatasetResult<PoseWriter> open(const std::string& path, PoseFormat format, const TargetsFile& targets);
  PoseWriter(PoseWriter&&) noexcept;
  PoseWriter& operator=(PoseWriter&&) noexcept;
  ~PoseWriter();

  DatasetResult<void> write(int64_t frame, const TargetPose& pose);  // at pose.mid_exposure_ns
  // Writes the rows kept since the last flush (call once per frame).
  DatasetResult<void> flush();
  // Flushes and closes.
  DatasetResult<void> close();

  size_t rows() const { return rows_; }

 private:
  PoseWriter() = default;
  struct File {
    std::string path;  // final path ("-": stdout)
    std::FILE* stream = nullptr;
    std::string pending;  // rows not yet flushed
  };
  DatasetResult<File*> file_for(int target_id);

  std::string path_;
  PoseFormat format_ = PoseFormat::kCsv;
  bool split_by_target_ = false;
  std::map<int, File> files_;  // key -1: the single file
  size_t rows_ = 0;
};

// One poses.csv line (with newline) / TUM line / JSON line for a pose.
std::string format_pose_line(PoseFormat format, int64_t frame, const TargetPose& pose);

}  // namespace tetrapulse
