// The overlay video (overlay_video.hpp).
#include "overlay_video.hpp"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

namespace tetrapulse::cli {

DatasetResult<OverlayVideo> OverlayVideo::create(const std::string& path, const CameraInfo& camera,
                                                 const TargetsFile& targets) {
  const std::string ext = std::filesystem::path(path).extension().string();
  int fourcc = 0;
  if (ext == ".avi" || ext == ".mkv") fourcc = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
  else if (ext == ".mp4") fourcc = cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  else return dataset_error(path, 0, "overlay video must end in .avi, .mp4 or .mkv");
  return OverlayVideo(path, fourcc, camera, targets);
}

DatasetResult<void> OverlayVideo::open(double fps, cv::Size size) {
  writer_ = std::make_unique<cv::VideoWriter>();
  size_ = size;
  bool ok = false;
  try {
    ok = writer_->open(path_, cv::CAP_FFMPEG, fourcc_, fps, size, true);
  } catch (const cv::Exception& e) {
    return dataset_error(path_, 0, std::string("cannot open the overlay video: ") + e.what());
  }
  if (!ok) return dataset_error(path_, 0, fmt::format("cannot open the overlay video ({}x{} at {:.1f} Hz)", size.width, size.height, fps));
  return {};
}

DatasetResult<void> OverlayVideo::write(const cv::Mat& image) {
  try {
    writer_->write(image);
  } catch (const cv::Exception& e) {
    return dataset_error(path_, 0, fmt::format("cannot write frame {} of the overlay video: {}", written_, e.what()));
  }
  ++written_;
  return {};
}

DatasetResult<void> OverlayVideo::add(const Frame& frame, const std::vector<TargetPose>& poses,
                                      const std::vector<OverlayPose>& truth) {
  if (frame.image.empty()) return {};
  std::vector<OverlayPose> measured;
  for (const TargetPose& p : poses)
    if (const Target* t = targets_.find(p.target_id)) measured.push_back({t, p.pose});
  cv::Mat drawn = overlay_frame(frame.image, camera_, measured, truth, fmt::format("frame {}", frame.frame));
  if (!writer_) {
    if (!pending_) {
      pending_ = drawn;
      first_ns_ = frame.timestamp_ns;
      return {};
    }
    const int64_t period = frame.timestamp_ns - *first_ns_;
    const double fps = period > 0 ? std::clamp(1e9 / double(period), 1.0, 1000.0) : 30.0;
    if (auto r = open(fps, pending_->size()); !r) return r;
    if (auto r = write(*pending_); !r) return r;
    pending_.reset();
  }
  if (drawn.size() != size_) {
    return dataset_error(path_, 0, fmt::format("{}: {}x{} image, the overlay video is {}x{}", frame.name, drawn.cols,
                                               drawn.rows, size_.width, size_.height));
  }
  return write(drawn);
}

DatasetResult<void> OverlayVideo::close() {
  if (pending_) {
    if (auto r = open(30.0, pending_->size()); !r) return r;
    if (auto r = write(*pending_); !r) return r;
    pending_.reset();
  }
  if (writer_) writer_->release();
  return {};
}

}  // namespace tetrapulse::cli
