#pragma once
// Reading and writing the files of a rig dataset (docs/rig-dataset.md), each
// checked field by field. Readers report the file, line and field of the first
// problem; writers round-trip every field (doubles in shortest exact form).
#include <cstdint>
#include <string>
#include <vector>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/datasets/dataset_error.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

// One row of frames.csv: the sensor integrated [timestamp_ns, timestamp_ns + exposure_ns).
struct FrameRecord {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;
  int64_t exposure_ns = 0;
  std::string file;  // relative to the dataset folder
};

// A pose as the CSV files hold it: translation (m) and unit Hamilton quaternion
// of R, with p_C = R p_T + t. Kept as written so files round-trip exactly.
struct PoseFields {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();

  Pose pose() const { return Pose::from_quaternion(q, t); }
  static PoseFields from(const Pose& p) { return PoseFields{p.t, p.quaternion()}; }
};

// One row of groundtruth.csv: pose of `target` in the camera at mid-exposure.
struct GroundTruthRecord {
  int64_t frame = 0;
  int target = 0;
  PoseFields pose;
};

// One row of poses.csv (localizer output).
struct PoseRecord {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;  // middle of the exposure
  int target = 0;
  PoseFields pose;
  int markers = 0;            // markers the pose used
  double reprojection_px = 0; // RMS reprojection error of those markers
};

DatasetResult<CameraInfo> read_camera_yaml(const std::string& path);
DatasetResult<CameraInfo> parse_camera_yaml(const std::string& text, const std::string& name);
std::string format_camera_yaml(const CameraInfo& camera);

DatasetResult<TargetsFile> read_targets_yaml(const std::string& path);
DatasetResult<TargetsFile> parse_targets_yaml(const std::string& text, const std::string& name);
std::string format_targets_yaml(const TargetsFile& targets);

// Rows must have strictly increasing frame numbers and timestamps. A malformed
// row is an error, or, given `skipped_lines`, left out and recorded there (its
// file:line and what is wrong); a missing file or a wrong header always fails.
DatasetResult<std::vector<FrameRecord>> read_frames_csv(const std::string& path,
                                                        std::vector<DatasetError>* skipped_lines = nullptr);
std::string format_frames_csv(const std::vector<FrameRecord>& frames);
// The header line of frames.csv, and one row (each with its newline).
std::string format_frames_header();
std::string format_frames_row(const FrameRecord& frame);

// A recording's timestamps (a video beside it): frames.csv without the file
// column, header frame,timestamp_ns,exposure_ns; the same checks. `file` is empty.
DatasetResult<std::vector<FrameRecord>> read_timestamps_csv(const std::string& path);

DatasetResult<std::vector<GroundTruthRecord>> read_groundtruth_csv(const std::string& path);
std::string format_groundtruth_csv(const std::vector<GroundTruthRecord>& rows);

DatasetResult<std::vector<PoseRecord>> read_poses_csv(const std::string& path);
std::string format_poses_csv_header();
std::string format_poses_csv_row(const PoseRecord& row);

// Reads a whole text file; error names the path.
DatasetResult<std::string> read_text_file(const std::string& path);
// Writes atomically (temporary file + rename) so a crash never leaves half a file.
DatasetResult<void> write_text_file(const std::string& path, const std::string& text);

}  // namespace tetrapulse
