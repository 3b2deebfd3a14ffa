#include "tetrapulse/datasets/rig_dataset.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace tetrapulse {

namespace fs = std::filesystem;

std::string RigDataset::path_of(const std::string& relative) const { return (fs::path(folder_) / relative).string(); }

DatasetResult<RigDataset> RigDataset::open(const std::string& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return dataset_error(folder, 0, "not a dataset folder (no such directory)");
  RigDataset d;
  d.folder_ = folder;
  auto camera = read_camera_yaml(d.path_of("camera.yaml"));
  if (!camera) return tl::unexpected(camera.error());
  d.camera_ = *camera;
  auto targets = read_targets_yaml(d.path_of("targets.yaml"));
  if (!targets) return tl::unexpected(targets.error());
  d.targets_ = std::move(*targets);
  auto frames = read_frames_csv(d.path_of("frames.csv"), &d.skipped_lines_);
  if (!frames) return tl::unexpected(frames.error());
  d.frames_ = std::move(*frames);
  const std::string gt = d.path_of("groundtruth.csv");
  if (fs::exists(gt, ec)) {
    auto rows = read_groundtruth_csv(gt);
    if (!rows) return tl::unexpected(rows.error());
    d.groundtruth_ = std::move(*rows);
    d.has_groundtruth_ = true;
  }
  return d;
}

DatasetResult<cv::Mat> RigDataset::load_image(size_t index, ImageMode mode) const {
  if (index >= frames_.size()) {
    return dataset_error(path_of("frames.csv"), 0, fmt::format("no frame at index {}", index));
  }
  if (mode == ImageMode::kForTargets) mode = targets_.needs_colour() ? ImageMode::kAsStored : ImageMode::kGrey;
  const std::string path = path_of(frames_[index].file);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return dataset_error(path, 0, fmt::format("image of frame {} is missing", frames_[index].frame));
  }
  if (fs::file_size(path, ec) == 0 && !ec) {
    return dataset_error(path, 0, fmt::format("image of frame {} is empty (0 bytes)", frames_[index].frame));
  }
  cv::Mat img;
  try {
    img = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    return dataset_error(path, 0, std::string("cannot decode image: ") + e.what());
  }
  if (img.empty()) return dataset_error(path, 0, "cannot decode image (truncated, or not a readable PNG)");
  const int depth = img.depth();
  if (img.channels() == 1) {
    if (depth != CV_8U && depth != CV_16U) return dataset_error(path, 0, "grey image must be 8- or 16-bit");
    if (mode == ImageMode::kAsStored && targets_.needs_colour()) {
      return dataset_error(path, 0, "grey image, but targets.yaml gives markers a colour: an 8-bit colour PNG is needed");
    }
  } else if (img.channels() == 3 || img.channels() == 4) {
    if (depth != CV_8U) return dataset_error(path, 0, "colour image must be 8-bit");
    if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2BGR);
    if (mode == ImageMode::kGrey) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  } else {
    return dataset_error(path, 0, fmt::format("unsupported image with {} channels", img.channels()));
  }
  if (img.cols != camera_.width || img.rows != camera_.height) {
    return dataset_error(path, 0, fmt::format("image is {}x{}, camera.yaml says {}x{}", img.cols, img.rows,
                                              camera_.width, camera_.height));
  }
  return img;
}

DatasetResult<RigDatasetWriter> RigDatasetWriter::create(const std::string& folder, const CameraInfo& camera,
                                                         const TargetsFile& targets) {
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "frames", ec);
  if (ec) return dataset_error(folder, 0, "cannot create dataset folder: " + ec.message());
  RigDatasetWriter w;
  w.folder_ = folder;
  w.camera_ = camera;
  w.targets_ = targets;
  const fs::path dir(folder);
  if (auto r = write_text_file((dir / "camera.yaml").string(), format_camera_yaml(camera)); !r) {
    return tl::unexpected(r.error());
  }
  if (auto r = write_text_file((dir / "targets.yaml").string(), format_targets_yaml(targets)); !r) {
    return tl::unexpected(r.error());
  }
  const std::string csv = (dir / "frames.csv").string();
  w.frames_csv_.open(csv, std::ios::binary | std::ios::trunc);
  w.frames_csv_ << format_frames_header() << std::flush;
  if (!w.frames_csv_) return dataset_error(csv, 0, std::string("cannot write: ") + std::strerror(errno));
  return w;
}

DatasetResult<void> RigDatasetWriter::add_frame(int64_t frame, int64_t timestamp_ns, int64_t exposure_ns,
                                                const cv::Mat& image) {
  const std::string rel = fmt::format("frames/{:06d}.png", frame);
  const std::string path = (fs::path(folder_) / rel).string();
  if (!frames_.empty() && (frame <= frames_.back().frame || timestamp_ns <= frames_.back().timestamp_ns)) {
    return dataset_error(path, 0, "frames must be added with increasing frame numbers and timestamps");
  }
  bool ok = false;
  try {
    // Fixed PNG settings so the same image always gives the same bytes.
    ok = cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
  } catch (const cv::Exception& e) {
    return dataset_error(path, 0, std::string("cannot write image: ") + e.what());
  }
  if (!ok) return dataset_error(path, 0, std::string("cannot write image: ") + std::strerror(errno));
  frames_.push_back(FrameRecord{frame, timestamp_ns, exposure_ns, rel});
  frames_csv_ << format_frames_row(frames_.back()) << std::flush;
  if (!frames_csv_) {
    return dataset_error(path_of_frames_csv(), 0, std::string("cannot append a row: ") + std::strerror(errno));
  }
  return {};
}

std::string RigDatasetWriter::path_of_frames_csv() const { return (fs::path(folder_) / "frames.csv").string(); }

DatasetResult<void> RigDatasetWriter::finish() {
  const fs::path dir(folder_);
  if (frames_csv_.is_open()) {
    frames_csv_.close();
    if (!frames_csv_) {
      return dataset_error(path_of_frames_csv(), 0, std::string("cannot close: ") + std::strerror(errno));
    }
  }
  if (!groundtruth_.empty()) {
    if (auto r = write_text_file((dir / "groundtruth.csv").string(), format_groundtruth_csv(groundtruth_)); !r) {
      return r;
    }
  }
  return {};
}

}  // namespace tetrapulse
