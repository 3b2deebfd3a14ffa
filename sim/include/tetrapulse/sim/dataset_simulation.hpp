#pragma once
// Runs a scenario and writes a rig dataset (docs/rig-dataset.md): camera.yaml,
// targets.yaml, frames.csv, frames/NNNNNN.png, groundtruth.csv (each target's pose
// in the camera at mid-exposure, left out while none of its markers is in the
// image), plus scenario.yaml, the scenario it came from (an extra file the
// contract allows). Frames render one after another on one thread; the same
// scenario and seed give the same bytes.
#include <cstdint>
#include <optional>
#include <string>

#include "tetrapulse/datasets/dataset_error.hpp"
#include "tetrapulse/sim/scenario.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace tetrapulse::sim {

struct SimulationOptions {
  std::string out;                  // dataset folder (created)
  std::optional<uint64_t> seed;     // default: the scenario's
  std::optional<int64_t> frames;    // frame numbers 0 .. frames - 1; default: the scenario's count
  bool ci = false;                  // use the scenario's ci_count (when frames is not given)
  BoardEmitterFactory board = default_board_emitter();  // what drives each target's LEDs
};

struct SimulationSummary {
  int64_t frames_written = 0;
  int64_t frames_dropped = 0;
  int64_t groundtruth_rows = 0;
  uint64_t seed = 0;
};

// True when frame `frame` is not delivered (listed, or drawn with drop_probability).
bool frame_dropped(const FrameSchedule& schedule, uint64_t seed, int64_t frame);

DatasetResult<SimulationSummary> simulate_dataset(const Scenario& scenario, const SimulationOptions& options);

}  // namespace tetrapulse::sim
