#pragma once
// A LocalizerStatus as diagnostic_msgs/msg/DiagnosticStatus entries (before they
// become DDS samples), the way ROS 2's diagnostics tools group them by name
// ("node: component"):
//   "<node>: localizer"  hardware_id = the camera frame; frames_matched,
//                        frames_dropped, targets_with_pose, processing_* and
//                        latency_* (ms, last/mean/max over the window)
//   "<node>: board <b>"  hardware_id = the board; target, sync_state, offset_ns,
//                        rate_ppm (keys present when known)
// Levels: a board that is synchronized or free-running is OK, acquiring or
// unknown WARN, lost ERROR; the localizer is WARN while frames were dropped in the
// window or no target has a pose, else OK.
#include <cstdint>
#include <string>
#include <vector>

#include "tetrapulse/ros2/localizer_status.hpp"

namespace tetrapulse::ros2 {

enum DiagnosticLevel : uint8_t { kDiagnosticOk = 0, kDiagnosticWarn = 1, kDiagnosticError = 2, kDiagnosticStale = 3 };

struct DiagnosticEntry {
  uint8_t level = kDiagnosticOk;
  std::string name;
  std::string message;
  std::string hardware_id;
  std::vector<std::pair<std::string, std::string>> values;
};

// `dropped_in_window`: frames dropped since the previous status (for the level).
std::vector<DiagnosticEntry> status_diagnostics(const LocalizerStatus& status, const std::string& node_name,
                                                const std::string& camera_frame, uint64_t dropped_in_window);

}  // namespace tetrapulse::ros2
