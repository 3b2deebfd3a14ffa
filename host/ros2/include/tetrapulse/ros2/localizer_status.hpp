#pragma once
// What /tetrapulse/status reports (diagnostic_msgs/msg/DiagnosticArray): a plain
// struct the localizer's owner fills, from a dataset replay with what a dataset
// knows, from a live camera loop with what the sync master and the camera know.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tetrapulse::ros2 {

enum class BoardSyncState {
  kUnknown,       // nothing heard from the board
  kSynchronized,  // the board's clock follows rig time (locked servo, or a synchronized dataset)
  kAcquiring,     // the servo is pulling in
  kFreeRunning,   // no sync: the localizer finds the board's phase and rate from the light
  kLost,          // was synchronized or tracked, is no longer
};
const char* board_sync_state_name(BoardSyncState state);

struct BoardSync {
  int target_id = -1;     // the target whose markers the board drives (-1: not known)
  std::string board;      // hardware id: "usb:SERIAL", "can:can0:3", or "target 3" from a dataset
  BoardSyncState state = BoardSyncState::kUnknown;
  // Board clock minus rig time (ns): the sync servo's offset live; for a
  // free-running board, its code origin (rig time of its bit 0) minus the time
  // base's epoch, as the localizer estimated it.
  std::optional<int64_t> offset_ns;
  std::optional<double> rate_ppm;  // board clock rate minus 1, parts per million
};

// Per-frame durations over the status window (ns).
struct DurationStats {
  uint64_t count = 0;
  int64_t last_ns = 0;
  int64_t max_ns = 0;
  int64_t total_ns = 0;
  void add(int64_t ns);
  int64_t mean_ns() const { return count == 0 ? 0 : total_ns / int64_t(count); }
};

// A live camera loop's own counts, in total (the loop's frames_dropped is made of them).
struct LiveFrameCounters {
  uint64_t frames_localized = 0;         // frames that reached the localizer
  uint64_t queue_drops = 0;              // dropped between capture and localizer (it fell behind)
  uint64_t bad_buffers = 0;              // incomplete or wrong-sized buffers from the camera
  uint64_t exposures_without_frame = 0;  // sync master: exposures no frame came from
  uint64_t frames_without_exposure = 0;  // frames no exposure matched
};

struct LocalizerStatus {
  int64_t rig_time_ns = 0;       // the newest frame's mid-exposure (the header stamp's source)
  std::vector<BoardSync> boards;
  // In total. A replay: frames with a rig timestamp that reached the localizer, and
  // gaps in frame numbers. Live: frames the exposure matcher stamped, and frames lost
  // before the localizer by the loop's counters (`live`).
  uint64_t frames_matched = 0;
  uint64_t frames_dropped = 0;
  std::optional<LiveFrameCounters> live;
  std::vector<int> targets_with_pose;  // targets posed in the newest frame
  // Over the window since the previous status:
  std::optional<DurationStats> processing;  // localizer time per frame (wall clock)
  std::optional<DurationStats> latency;     // mid-exposure to poses published (live only)
};

}  // namespace tetrapulse::ros2
