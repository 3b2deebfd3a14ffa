#include "tetrapulse/host/recorded_frames.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace tetrapulse::host {
namespace {

bool parse_int(const std::string& text, int64_t* out) {
  try {
    size_t used = 0;
    const long long v = std::stoll(text, &used);
    if (used != text.size()) return false;
    *out = v;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

HostResult<std::vector<FrameRecord>> frames_from_exposures(const std::vector<Exposure>& exposures,
                                                           const std::vector<CapturedImage>& images,
                                                           const FrameMatchOptions& options) {
  for (size_t k = 1; k < exposures.size(); ++k) {
    if (exposures[k].timestamp_ns <= exposures[k - 1].timestamp_ns || exposures[k].frame <= exposures[k - 1].frame) {
      return host_error(HostErrorKind::kBadInput, "exposures",
                        fmt::format("frame {} at {} ns does not follow frame {} at {} ns", exposures[k].frame,
                                    exposures[k].timestamp_ns, exposures[k - 1].frame, exposures[k - 1].timestamp_ns));
    }
  }
  // Exposure index -> image, in exposure order.
  std::vector<const CapturedImage*> image_of(exposures.size(), nullptr);
  for (const CapturedImage& image : images) {
    // The latest exposure that ended at or before the image arrived.
    const auto after = std::upper_bound(exposures.begin(), exposures.end(), image.arrived_ns,
                                        [](int64_t t, const Exposure& e) { return t < e.timestamp_ns + e.exposure_ns; });
    if (after == exposures.begin()) {
      return host_error(HostErrorKind::kBadInput, image.file,
                        fmt::format("arrived at {} ns, before any exposure ended", image.arrived_ns));
    }
    const size_t k = static_cast<size_t>(after - exposures.begin()) - 1;
    const int64_t delay = image.arrived_ns - (exposures[k].timestamp_ns + exposures[k].exposure_ns);
    if (delay > options.max_delay_ns) {
      return host_error(HostErrorKind::kBadInput, image.file,
                        fmt::format("arrived {} ns after the last exposure ended (frame {}), more than {} ns", delay,
                                    exposures[k].frame, options.max_delay_ns));
    }
    if (image_of[k] != nullptr) {
      return host_error(HostErrorKind::kBadInput, image.file,
                        fmt::format("comes from the same exposure (frame {}) as {}", exposures[k].frame,
                                    image_of[k]->file));
    }
    image_of[k] = &image;
  }
  std::vector<FrameRecord> frames;
  for (size_t k = 0; k < exposures.size(); ++k) {
    if (image_of[k] == nullptr) continue;
    FrameRecord r;
    r.frame = exposures[k].frame;
    r.timestamp_ns = exposures[k].timestamp_ns;
    r.exposure_ns = exposures[k].exposure_ns;
    r.file = image_of[k]->file;
    frames.push_back(r);
  }
  if (!frames.empty()) {
    const int64_t first = frames.front().frame;
    for (FrameRecord& r : frames) r.frame -= first;
  }
  return frames;
}

HostResult<std::vector<Exposure>> read_exposures_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return host_error(HostErrorKind::kBadFile, path, "is a folder, not a file");
  std::ifstream in(path);
  if (!in) return host_error(HostErrorKind::kBadFile, path, "cannot read the file");
  std::string line;
  if (!std::getline(in, line) || line != "frame,timestamp_ns,exposure_ns") {
    return host_error(HostErrorKind::kBadFile, path + ":1", "expected the header frame,timestamp_ns,exposure_ns");
  }
  std::vector<Exposure> exposures;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::stringstream fields(line);
    std::string f[3];
    Exposure e;
    const bool ok = std::getline(fields, f[0], ',') && std::getline(fields, f[1], ',') && std::getline(fields, f[2]) &&
                    parse_int(f[0], &e.frame) && parse_int(f[1], &e.timestamp_ns) && parse_int(f[2], &e.exposure_ns) &&
                    e.exposure_ns > 0;
    if (!ok) {
      return host_error(HostErrorKind::kBadFile, fmt::format("{}:{}", path, number),
                        fmt::format("'{}': expected FRAME,TIMESTAMP_NS,EXPOSURE_NS (integers, exposure > 0)", line));
    }
    exposures.push_back(e);
  }
  return exposures;
}

HostResult<void> write_frames_csv(const std::string& dataset_dir, const std::vector<FrameRecord>& frames) {
  const std::string path = (std::filesystem::path(dataset_dir) / "frames.csv").string();
  auto written = write_text_file(path, format_frames_csv(frames));
  if (!written) return host_error(HostErrorKind::kBadFile, path, written.error().what());
  return {};
}

}  // namespace tetrapulse::host
