#pragma once
// A rig dataset folder (docs/rig-dataset.md): reading it for the localizer and
// evaluation, and writing one for the simulator and recorders.
#include <optional>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {

class RigDataset {
 public:
  // Reads and checks camera.yaml, targets.yaml, frames.csv and (when present)
  // groundtruth.csv. Images are read lazily by load_image(). A malformed line
  // of frames.csv costs only its frame: it is left out and listed in
  // skipped_lines().
  static DatasetResult<RigDataset> open(const std::string& folder);

  const std::string& folder() const { return folder_; }
  const CameraInfo& camera() const { return camera_; }
  const TargetsFile& targets() const { return targets_; }
  const std::vector<FrameRecord>& frames() const { return frames_; }
  const std::vector<GroundTruthRecord>& groundtruth() const { return groundtruth_; }
  bool has_groundtruth() const { return has_groundtruth_; }
  // The frames.csv lines left out, each naming file:line and what is wrong.
  const std::vector<DatasetError>& skipped_lines() const { return skipped_lines_; }

  enum class ImageMode {
    kGrey,      // 8- or 16-bit single channel; colour converted to 8-bit grey (the contract)
    kAsStored,  // as in the file (colour kept as 8-bit BGR)
    kForTargets,  // kAsStored when some marker of targets.yaml has a colour, else kGrey
  };
  // Image of frames()[index]; the error names the file when it is missing,
  // empty, truncated or otherwise undecodable, of an unsupported type or not
  // camera-sized.
  DatasetResult<cv::Mat> load_image(size_t index, ImageMode mode = ImageMode::kForTargets) const;

  std::string path_of(const std::string& relative) const;

 private:
  std::string folder_;
  CameraInfo camera_;
  TargetsFile targets_;
  std::vector<FrameRecord> frames_;
  std::vector<GroundTruthRecord> groundtruth_;
  std::vector<DatasetError> skipped_lines_;
  bool has_groundtruth_ = false;
};

// Writes a dataset folder: images as they come, the CSV and YAML files on finish().
class RigDatasetWriter {
 public:
  // Creates `folder` and `folder/frames`, writes camera.yaml and targets.yaml and
  // starts frames.csv (its header); fails, naming the file, when one cannot be written.
  // From then on the folder is a dataset: a recording that dies keeps every frame
  // added so far.
  static DatasetResult<RigDatasetWriter> create(const std::string& folder, const CameraInfo& camera,
                                                const TargetsFile& targets);

  // Writes frames/NNNNNN.png (8- or 16-bit grey, or 8-bit BGR), then appends its
  // row to frames.csv and flushes it (to the OS: a crash of the process loses none).
  DatasetResult<void> add_frame(int64_t frame, int64_t timestamp_ns, int64_t exposure_ns, const cv::Mat& image);
  void add_groundtruth(const GroundTruthRecord& row) { groundtruth_.push_back(row); }

  // Closes frames.csv and writes groundtruth.csv (if any rows).
  DatasetResult<void> finish();

  const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  CameraInfo camera_;
  TargetsFile targets_;
  std::vector<FrameRecord> frames_;
  std::vector<GroundTruthRecord> groundtruth_;
  std::string path_of_frames_csv() const;

  std::ofstream frames_csv_;  // open from create() to finish()
};

}  // namespace tetrapulse
