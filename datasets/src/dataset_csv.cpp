// frames.csv, groundtruth.csv and poses.csv (docs/rig-dataset.md).
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include <fmt/format.h>

#include "csv_table.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {

namespace {

constexpr const char* kFramesHeader = "frame,timestamp_ns,exposure_ns,file";
constexpr const char* kTimestampsHeader = "frame,timestamp_ns,exposure_ns";
constexpr const char* kGroundTruthHeader = "frame,target,x,y,z,qx,qy,qz,qw";
constexpr const char* kPosesHeader = "frame,timestamp_ns,target,x,y,z,qx,qy,qz,qw,markers,reprojection_px";

// x,y,z,qx,qy,qz,qw starting at column `col`; the quaternion must be unit length.
PoseFields read_pose(csv::FieldReader& r, size_t col) {
  const double x = r.number(col, "x"), y = r.number(col + 1, "y"), z = r.number(col + 2, "z");
  const double qx = r.number(col + 3, "qx"), qy = r.number(col + 4, "qy"), qz = r.number(col + 5, "qz"),
               qw = r.number(col + 6, "qw");
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!r.failed() && std::abs(q.norm() - 1.0) > 1e-6) {
    r.fail(fmt::format("qx,qy,qz,qw: not a unit quaternion (norm {})", q.norm()));
  }
  return r.failed() ? PoseFields{} : PoseFields{Eigen::Vector3d(x, y, z), q};
}

std::string format_pose(const PoseFields& p) {
  const Eigen::Quaterniond& q = p.q;
  return fmt::format("{},{},{},{},{},{},{}", p.t.x(), p.t.y(), p.t.z(), q.x(), q.y(), q.z(), q.w());
}

template <typename T>
DatasetResult<T> read_table(const std::string& path, const char* header,
                            const std::function<std::optional<DatasetError>(const csv::Table&, T*)>& body,
                            std::vector<DatasetError>* bad_rows = nullptr) {
  auto text = read_text_file(path);
  if (!text) return tl::unexpected(text.error());
  auto table = csv::Table::parse(*text, path, header, bad_rows);
  if (!table) return tl::unexpected(table.error());
  T out;
  if (auto err = body(*table, &out)) return tl::unexpected(*err);
  return out;
}

}  // namespace

namespace {

// frame,timestamp_ns,exposure_ns (the first columns of frames.csv and of a
// recording's timestamps), each row after `prev` in frame number and time.
bool read_timing(csv::FieldReader& r, const std::vector<FrameRecord>& prev, FrameRecord* f) {
  f->frame = r.integer(0, "frame");
  f->timestamp_ns = r.integer(1, "timestamp_ns");
  f->exposure_ns = r.integer(2, "exposure_ns");
  if (!r.failed() && f->frame < 0) r.fail(fmt::format("frame: must be non-negative, got {}", f->frame));
  if (!r.failed() && f->exposure_ns <= 0) r.fail(fmt::format("exposure_ns: must be positive, got {}", f->exposure_ns));
  if (!r.failed() && !prev.empty()) {
    const FrameRecord& p = prev.back();
    if (f->frame <= p.frame) {
      r.fail(fmt::format("frame: {} does not follow {} (frame numbers must increase)", f->frame, p.frame));
    } else if (f->timestamp_ns == p.timestamp_ns) {
      r.fail(fmt::format("timestamp_ns: {} duplicates frame {}", f->timestamp_ns, p.frame));
    } else if (f->timestamp_ns < p.timestamp_ns) {
      r.fail(fmt::format("timestamp_ns: {} is earlier than frame {}'s {} (timestamps must increase)", f->timestamp_ns,
                         p.frame, p.timestamp_ns));
    }
  }
  return !r.failed();
}

}  // namespace

DatasetResult<std::vector<FrameRecord>> read_frames_csv(const std::string& path,
                                                        std::vector<DatasetError>* skipped_lines) {
  using Rows = std::vector<FrameRecord>;
  const auto rows = [skipped_lines](const csv::Table& t, Rows* out) -> std::optional<DatasetError> {
    for (const auto& row : t.rows()) {
      csv::FieldReader r(t, row);
      FrameRecord f;
      if (read_timing(r, *out, &f)) {
        f.file = r.text(3);
        if (f.file.empty()) r.fail("file: empty");
      }
      if (r.failed()) {
        if (!skipped_lines) return r.error();
        skipped_lines->push_back(r.error());
        continue;
      }
      out->push_back(std::move(f));
    }
    return std::nullopt;
  };
  auto out = read_table<Rows>(path, kFramesHeader, rows, skipped_lines);
  // Line order: the rows' own errors come after those of the split.
  if (skipped_lines) {
    std::stable_sort(skipped_lines->begin(), skipped_lines->end(),
                     [](const DatasetError& a, const DatasetError& b) { return a.line < b.line; });
  }
  return out;
}

DatasetResult<std::vector<FrameRecord>> read_timestamps_csv(const std::string& path) {
  using Rows = std::vector<FrameRecord>;
  return read_table<Rows>(path, kTimestampsHeader, [](const csv::Table& t, Rows* out) -> std::optional<DatasetError> {
    for (const auto& row : t.rows()) {
      csv::FieldReader r(t, row);
      FrameRecord f;
      if (!read_timing(r, *out, &f)) return r.error();
      out->push_back(std::move(f));
    }
    return std::nullopt;
  });
}

std::string format_frames_header() { return std::string(kFramesHeader) + "\n"; }

std::string format_frames_row(const FrameRecord& f) {
  return fmt::format("{},{},{},{}\n", f.frame, f.timestamp_ns, f.exposure_ns, f.file);
}

std::string format_frames_csv(const std::vector<FrameRecord>& frames) {
  std::string out = format_frames_header();
  for (const auto& f : frames) out += format_frames_row(f);
  return out;
}

DatasetResult<std::vector<GroundTruthRecord>> read_groundtruth_csv(const std::string& path) {
  using Rows = std::vector<GroundTruthRecord>;
  return read_table<Rows>(path, kGroundTruthHeader, [](const csv::Table& t, Rows* out) -> std::optional<DatasetError> {
    for (const auto& row : t.rows()) {
      csv::FieldReader r(t, row);
      GroundTruthRecord g;
      g.frame = r.integer(0, "frame");
      g.target = static_cast<int>(r.integer(1, "target"));
      g.pose = read_pose(r, 2);
      if (r.failed()) return r.error();
      out->push_back(g);
    }
    return std::nullopt;
  });
}

std::string format_groundtruth_csv(const std::vector<GroundTruthRecord>& rows) {
  std::string out = std::string(kGroundTruthHeader) + "\n";
  for (const auto& g : rows) out += fmt::format("{},{},{}\n", g.frame, g.target, format_pose(g.pose));
  return out;
}

DatasetResult<std::vector<PoseRecord>> read_poses_csv(const std::string& path) {
  using Rows = std::vector<PoseRecord>;
  return read_table<Rows>(path, kPosesHeader, [](const csv::Table& t, Rows* out) -> std::optional<DatasetError> {
    for (const auto& row : t.rows()) {
      csv::FieldReader r(t, row);
      PoseRecord p;
      p.frame = r.integer(0, "frame");
      p.timestamp_ns = r.integer(1, "timestamp_ns");
      p.target = static_cast<int>(r.integer(2, "target"));
      p.pose = read_pose(r, 3);
      p.markers = static_cast<int>(r.integer(10, "markers"));
      p.reprojection_px = r.number(11, "reprojection_px");
      if (r.failed()) return r.error();
      out->push_back(p);
    }
    return std::nullopt;
  });
}

std::string format_poses_csv_header() { return std::string(kPosesHeader) + "\n"; }

std::string format_poses_csv_row(const PoseRecord& p) {
  return fmt::format("{},{},{},{},{},{}\n", p.frame, p.timestamp_ns, p.target, format_pose(p.pose), p.markers,
                     p.reprojection_px);
}

}  // namespace tetrapulse
