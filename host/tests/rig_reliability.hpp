#pragma once
// The virtual rig (HostSyncedRig: simulated boards configured and synchronised by the
// host's Board, GpioSync and CanSync) over long stretches of rig time, for the reliability
// tests and the soak tool: every board's true clock error against rig time, its state as
// the host reads it over its link, the trigger's exposures and the process's memory.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/sim_rig.hpp"
#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/sim/scenario.hpp"

namespace tetrapulse::host::testing {

// swarm's four targets with their boards on GPIO, CAN, GPIO and CAN, or
// only the first `targets` of them.
sim::Scenario mixed_sync_scenario(size_t targets = 4);

// A synced board's rig time for its own counter now minus the true rig time (ns).
int64_t board_clock_error_ns(const sim_board::SimBoard& board);

// The camera on the rig: frames rendered from the boards' LEDs (the renderer runs the rig
// as far as each frame needs), localized by one Localizer in frame order.
class RigCamera {
 public:
  RigCamera(const sim::Scenario& scenario, const std::shared_ptr<HostSyncedRig>& rig);
  ~RigCamera();
  // Frame `frame`'s poses; nullopt when the localizer refused it.
  std::optional<std::vector<TargetPose>> localize(int64_t frame);

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

struct SoakBoard {
  sim::BoardSync sync = sim::BoardSync::kNone;
  int64_t max_abs_error_ns = 0;  // after lock, synced boards
  uint64_t not_locked = 0;       // status reads after the first lock that were not locked
  uint64_t led_changes = 0;      // applied over the run (a stalled board stops changing)
  uint64_t status_failures = 0;  // status requests over the host link that failed
};

// The localizer on the rig's frames: a burst of consecutive frames rendered from the
// boards' LEDs every minute, into one Localizer that lives the whole run.
struct SoakLocalizer {
  uint64_t frames = 0;           // rendered and localized
  uint64_t frame_errors = 0;     // frames the localizer refused
  uint64_t poses = 0;
  // Poses of each burst's frames after its first kSettleFrames (identification). Which
  // frames can give a pose depends on the codes (a dark marker is not seen), so bursts are
  // compared with each other: the last as many as the first.
  std::vector<uint64_t> burst_poses;
  static constexpr int kSettleFrames = 15;
};

struct SoakReport {
  int64_t rig_seconds = 0;
  uint64_t exposures = 0, expected_exposures = 0;
  uint64_t can_syncs = 0;
  // After 60 s and at the end: the heap in use (malloc's count of live bytes: what a leak
  // grows) and the resident set (which also holds what the allocator keeps for reuse).
  long heap_kib_after_warmup = 0, heap_kib_end = 0;
  long rss_kib_after_warmup = 0, rss_kib_end = 0;
  std::vector<SoakBoard> boards;
  SoakLocalizer localizer;
  std::string failure;  // the rig's first error, empty when none
};

// Runs `scenario`'s rig for `rig_seconds` from frame 0, reading every board's status over
// its host link and its true clock error once a rig second, forgetting what lies a second
// behind (so only leaks grow memory), and localizing `burst_frames` consecutive frames at
// the start of every minute (0: none). `progress` (may be null) gets each minute's line.
SoakReport soak(const sim::Scenario& scenario, int64_t rig_seconds, int burst_frames,
                void (*progress)(const std::string&) = nullptr);

// Resident set size of this process (KiB), from /proc/self/statm.
long resident_kib();
// Heap bytes in use (KiB), from mallinfo2: allocated and not yet freed.
long heap_in_use_kib();

}  // namespace tetrapulse::host::testing
