#include "tetrapulse/datasets/pose_writer.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {

const char* pose_format_name(PoseFormat format) {
  switch (format) {
    case PoseFormat::kCsv: return "csv";
    case PoseFormat::kTum: return "tum";
    case PoseFormat::kJsonLines: return "jsonl";
  }
  return "csv";
}

std::string format_pose_line(PoseFormat format, int64_t frame, const TargetPose& pose) {
  const int64_t mid_exposure_ns = pose.mid_exposure_ns;
  const PoseFields f = PoseFields::from(pose.pose);
  switch (format) {
    case PoseFormat::kCsv: {
      PoseRecord row;
      row.frame = frame;
      row.timestamp_ns = mid_exposure_ns;
      row.target = pose.target_id;
      row.pose = f;
      row.markers = pose.markers;
      row.reprojection_px = pose.rms_px;
      return format_poses_csv_row(row);
    }
    case PoseFormat::kTum:
      return fmt::format("{}.{:09d} {} {} {} {} {} {} {}\n", mid_exposure_ns / 1'000'000'000,
                         std::abs(mid_exposure_ns % 1'000'000'000), f.t.x(), f.t.y(), f.t.z(), f.q.x(), f.q.y(),
                         f.q.z(), f.q.w());
    case PoseFormat::kJsonLines: {
      std::string covariance = "null";
      if (pose.has_covariance) {
        covariance = "[";
        for (int i = 0; i < 36; ++i) covariance += fmt::format("{}{}", i ? "," : "", pose.covariance(i / 6, i % 6));
        covariance += "]";
      }
      return fmt::format(
          "{{\"frame\":{},\"timestamp_ns\":{},\"target\":{},\"status\":\"{}\",\"markers\":{},\"reprojection_px\":{},"
          "\"t\":[{},{},{}],\"q\":[{},{},{},{}],\"covariance\":{}}}\n",
          frame, mid_exposure_ns, pose.target_id, pose_status_name(pose.status), pose.markers, pose.rms_px, f.t.x(),
          f.t.y(), f.t.z(), f.q.x(), f.q.y(), f.q.z(), f.q.w(), covariance);
    }
  }
  return {};
}

DatasetResult<PoseWriter> PoseWriter::open(const std::string& path, PoseFormat format, const TargetsFile& targets) {
  PoseWriter w;
  w.path_ = path;
  w.format_ = format;
  w.split_by_target_ = format == PoseFormat::kTum && targets.targets.size() > 1 && path != "-";
  if (!w.split_by_target_) {
    auto f = w.file_for(-1);
    if (!f) return tl::unexpected(f.error());
    if (format == PoseFormat::kCsv) (*f)->pending = format_poses_csv_header();
    if (auto r = w.flush(); !r) return tl::unexpected(r.error());
  }
  return w;
}

PoseWriter::PoseWriter(PoseWriter&&) noexcept = default;
PoseWriter& PoseWriter::operator=(PoseWriter&&) noexcept = default;

PoseWriter::~PoseWriter() {
  // Not closed (an error): keep what was flushed, whole frames only.
  for (auto& [key, file] : files_) {
    if (file.stream && file.path != "-") std::fclose(file.stream);
  }
}

DatasetResult<PoseWriter::File*> PoseWriter::file_for(int target_id) {
  const int key = split_by_target_ ? target_id : -1;
  auto it = files_.find(key);
  if (it != files_.end()) return &it->second;
  File file;
  if (path_ == "-") {
    file.path = "-";
    file.stream = stdout;
  } else {
    if (split_by_target_) {
      const std::filesystem::path p(path_);
      file.path = (p.parent_path() / fmt::format("{}.target{}{}", p.stem().string(), target_id, p.extension().string()))
                      .string();
    } else {
      file.path = path_;
    }
    file.stream = std::fopen(file.path.c_str(), "w");
    if (!file.stream) return dataset_error(file.path, 0, std::string("cannot write: ") + std::strerror(errno));
  }
  return &files_.emplace(key, file).first->second;
}

DatasetResult<void> PoseWriter::write(int64_t frame, const TargetPose& pose) {
  auto file = file_for(pose.target_id);
  if (!file) return tl::unexpected(file.error());
  (*file)->pending += format_pose_line(format_, frame, pose);
  ++rows_;
  return {};
}

DatasetResult<void> PoseWriter::flush() {
  for (auto& [key, file] : files_) {
    if (!file.stream || file.pending.empty()) continue;
    const bool ok = std::fwrite(file.pending.data(), 1, file.pending.size(), file.stream) == file.pending.size() &&
                    std::fflush(file.stream) == 0;
    file.pending.clear();
    if (!ok) return dataset_error(file.path, 0, std::string("cannot write: ") + std::strerror(errno));
  }
  return {};
}

DatasetResult<void> PoseWriter::close() {
  auto flushed = flush();
  for (auto& [key, file] : files_) {
    if (!file.stream || file.path == "-") continue;
    const bool ok = std::fclose(file.stream) == 0;
    file.stream = nullptr;
    if (flushed && !ok) flushed = dataset_error(file.path, 0, std::string("cannot write: ") + std::strerror(errno));
  }
  return flushed;
}

}  // namespace tetrapulse
