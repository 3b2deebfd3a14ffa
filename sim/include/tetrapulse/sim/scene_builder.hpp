#pragma once
// From a scenario to the scene the renderer draws: trajectories (seeded), the
// contract's code emitter for each target board wrapped in its occlusions, and
// flickering lamps for distractors. Bodies: 0 .. targets - 1 are the targets in
// targets.yaml order, then the distractors.
#include <cstdint>

#include "tetrapulse/sim/scenario.hpp"
#include "tetrapulse/sim/scene.hpp"

namespace tetrapulse::sim {

Scene build_scene(const Scenario& scenario, uint64_t seed);

}  // namespace tetrapulse::sim
