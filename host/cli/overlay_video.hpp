#pragma once
// `--overlay FILE`: a video of the frames with each reported target drawn over them
// (its markers and axes projected from the pose, its id; pose_overlay.hpp), and the
// true poses too where a dataset has them. The writer opens on the second frame,
// when the frame rate is known from the two stamps (one frame only: 30 Hz). Codec by
// the file's extension: .avi Motion JPEG, .mp4 MPEG-4 part 2, .mkv Motion JPEG.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/videoio.hpp>

#include "pose_overlay.hpp"
#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace tetrapulse::cli {

class OverlayVideo {
 public:
  // kBadInput naming `path` when its extension is none of .avi, .mp4, .mkv.
  static DatasetResult<OverlayVideo> create(const std::string& path, const CameraInfo& camera, const TargetsFile& targets);

  // One frame with its poses (and true poses, if any). Error: names the file.
  DatasetResult<void> add(const Frame& frame, const std::vector<TargetPose>& poses, const std::vector<OverlayPose>& truth = {});
  // Writes what is pending and closes the file; frames() of them in it.
  DatasetResult<void> close();
  size_t frames() const { return written_; }
  const std::string& path() const { return path_; }

 private:
  OverlayVideo(std::string path, int fourcc, const CameraInfo& camera, const TargetsFile& targets)
      : path_(std::move(path)), fourcc_(fourcc), camera_(camera), targets_(targets) {}
  DatasetResult<void> open(double fps, cv::Size size);
  DatasetResult<void> write(const cv::Mat& image);

  std::string path_;
  int fourcc_;
  CameraModel camera_;
  TargetsFile targets_;
  std::unique_ptr<cv::VideoWriter> writer_;
  cv::Size size_;
  std::optional<cv::Mat> pending_;    // the first frame, until the rate is known
  std::optional<int64_t> first_ns_;
  size_t written_ = 0;
};

}  // namespace tetrapulse::cli
