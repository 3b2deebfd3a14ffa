#include "tetrapulse/host/exposure.hpp"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::host {

HostResult<std::unique_ptr<ExposureLogWriter>> ExposureLogWriter::create(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return host_error(HostErrorKind::kBadFile, path, fmt::format("cannot write: {}", std::strerror(errno)));
  std::unique_ptr<ExposureLogWriter> w(new ExposureLogWriter(path, f));
  if (std::fputs("frame,timestamp_ns,exposure_ns\n", f) < 0 || std::fflush(f) != 0) {
    return host_error(HostErrorKind::kBadFile, path, fmt::format("cannot write: {}", std::strerror(errno)));
  }
  return w;
}

ExposureLogWriter::~ExposureLogWriter() { std::fclose(file_); }

HostResult<void> ExposureLogWriter::write(const Exposure& e) {
  if (std::fprintf(file_, "%lld,%lld,%lld\n", static_cast<long long>(e.frame), static_cast<long long>(e.timestamp_ns),
                   static_cast<long long>(e.exposure_ns)) < 0 ||
      std::fflush(file_) != 0) {
    return host_error(HostErrorKind::kBadFile, path_, fmt::format("cannot write: {}", std::strerror(errno)));
  }
  return {};
}

std::optional<Exposure> StrobeEdgePairer::edge(bool active, int64_t rig_ns) {
  if (active) {
    start_ns_ = rig_ns;
    return std::nullopt;
  }
  if (!start_ns_) return std::nullopt;  // the strobe was already active when we started
  const int64_t start = *start_ns_;
  start_ns_.reset();
  if (!first_ns_) first_ns_ = start;
  Exposure e;
  e.timestamp_ns = start;
  e.exposure_ns = rig_ns - start;
  // Nearest whole number of periods since the first exposure.
  e.frame = period_ns_ > 0 ? protocol::floor_div(start - *first_ns_ + period_ns_ / 2, period_ns_) : count_;
  ++count_;
  return e;
}

}  // namespace tetrapulse::host
