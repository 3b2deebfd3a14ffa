#pragma once
// A scenario: everything the virtual rig needs to write a rig dataset — the
// camera and how it moves, the sensor, the frames, the targets (their
// targets.yaml contents plus motion, board clock, brightness and occlusions) and
// disturbances (distractor lamps, dropped frames). Read from YAML by
// scenario_yaml.hpp; the format is documented in sim/SCENARIOS.md.
// Units: metres, integer nanoseconds of rig time (seconds as doubles where the
// file says _s), radians (degrees in files, where the field name says _deg).
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/code_clock.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/sim/board_clock.hpp"
#include "tetrapulse/sim/flicker_emitter.hpp"
#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/motion.hpp"
#include "tetrapulse/sim/sensor_model.hpp"
#include "tetrapulse/sim/time_intervals.hpp"

namespace tetrapulse::sim {

struct FrameSchedule {
  int64_t start_ns = 0;            // start of frame 0's exposure
  int64_t period_ns = 10'000'000;  // frame k starts at start_ns + k period_ns
  int64_t exposure_ns = 2'000'000;
  int64_t count = 100;             // frame numbers 0 .. count - 1 (full size)
  int64_t ci_count = 60;           // the CI-sized variant
  std::vector<int64_t> dropped;    // frame numbers never delivered (absent from frames.csv)
  double drop_probability = 0;     // each other frame is dropped with this probability (seeded)
};

// What the simulator knows about a target beyond targets.yaml.
struct TargetSimulation {
  MotionSpec motion;                  // the target's pose in the world
  double radiance_e_per_ms = 1600;    // electrons per fully covered pixel per ms at full emission
  // LED beam: radiance scales with cos(angle between beam_axis and the direction
  // to the camera)^beam_exponent, zero behind (0: a uniform sphere; 1: Lambertian).
  double beam_exponent = 0;
  Eigen::Vector3d beam_axis_B = Eigen::Vector3d::UnitZ();  // body frame, unit
  // Per-marker brightness spread: each marker's radiance is multiplied by
  // exp(radiance_spread N(0,1)) drawn once from the seed (0: all alike).
  double radiance_spread = 0;
  // Painted balls instead of LEDs (passive markers): electrons per fully covered
  // pixel per ms where the surface faces the scene's light squarely (unset: LEDs).
  std::optional<double> paint_e_per_ms;
  // Its markers' colour: their light's share in R, G, B of a Bayer sensor, each
  // 0..1 (a grey sensor takes the mean) [1 1 1].
  Eigen::Vector3d rgb = Eigen::Vector3d::Ones();
  BoardClockSpec clock;               // its board's clock (free_running follows the time base)
  std::array<TimeIntervals, 4> occluded;  // per marker: when it is hidden from the camera
};

struct Distractor {
  std::string name;
  double diameter_m = 0.02;
  double radiance_e_per_ms = 1000;
  Flicker flicker;
  MotionSpec motion;
};

struct Scenario {
  std::string name;
  std::string description;
  uint64_t seed = 1;  // default seed (the command line may override it)
  FrameSchedule frames;
  CameraInfo camera;
  MotionSpec camera_motion;
  RenderSettings render;
  SensorConfig sensor;
  TargetsFile targets;                   // written to targets.yaml as is
  std::vector<TargetSimulation> simulation;  // one per targets.targets entry, same order
  std::vector<Distractor> distractors;
  // The light painted markers reflect (`lighting:`): world direction to a distant
  // source, unit, and the share of it on their shadowed side.
  Eigen::Vector3d light_direction_W = Eigen::Vector3d::UnitZ();
  double ambient = 0.3;
  std::string source_text;  // the YAML it was read from
};

// The bit clocks (code_clock.hpp) of the scenario's free-running boards, by target
// id, from b(t) = offset + t (1 + ppm 1e-6) (board_clock.hpp): what an evaluation
// needs to count the frames whose markers are truly lit. Synchronized boards: none.
std::map<int, CodeClock> free_running_code_clocks(const Scenario& scenario);

}  // namespace tetrapulse::sim
