// Camera: counting and spec parsing shared by every backend.
#include "tetrapulse/host/camera.hpp"

namespace tetrapulse::host {

HostResult<std::optional<CameraFrame>> Camera::grab(int timeout_ms) {
  auto f = do_grab(timeout_ms);
  if (f && *f) {
    ++counters_.frames;
    if ((*f)->bad) ++counters_.bad_buffers;
  }
  return f;
}

HostResult<CameraSpec> parse_camera_spec(const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos || colon + 1 == spec.size()) {
    return host_error(HostErrorKind::kBadInput, spec, "camera must be aravis:ID (device id or IP address) or v4l2:/dev/videoN");
  }
  CameraSpec s{spec.substr(0, colon), spec.substr(colon + 1)};
  if (s.backend != "aravis" && s.backend != "v4l2") {
    return host_error(HostErrorKind::kBadInput, spec, "unknown camera backend '" + s.backend + "' (aravis or v4l2)");
  }
  return s;
}

HostResult<std::unique_ptr<Camera>> open_camera(const std::string& spec) {
  auto s = parse_camera_spec(spec);
  if (!s) return tl::unexpected(s.error());
  if (s->backend == "aravis") return open_aravis_camera(s->address);
  return open_v4l2_camera(s->address);
}

}  // namespace tetrapulse::host
