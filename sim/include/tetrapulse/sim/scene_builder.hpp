#pragma once
// From a scenario to the scene the renderer draws: trajectories (seeded), the
// contract's code emitter for each target board wrapped in its occlusions, and
// flickering lamps for distractors. Bodies: 0 .. targets - 1 are the targets in
// targets.yaml order, then the distractors.
#include <cstdint>
#include <functional>
#include <memory>

#include "tetrapulse/sim/scenario.hpp"
#include "tetrapulse/sim/scene.hpp"

namespace tetrapulse::sim {

// The light of target `index`'s board (its four markers as lights 0..3). The
// default plays the contract's formula (CodeEmitter); a simulated board running
// the firmware's code player plugs in here, the renderer unchanged. Occlusions
// are applied around whatever it returns.
using BoardEmitterFactory =
    std::function<std::unique_ptr<LedEmitter>(const TargetsFile& targets, size_t index, const BoardClockSpec& clock)>;
std::unique_ptr<LedEmitter> contract_board_emitter(const TargetsFile& targets, size_t index, const BoardClockSpec& clock);

Scene build_scene(const Scenario& scenario, uint64_t seed, const BoardEmitterFactory& board = contract_board_emitter);

}  // namespace tetrapulse::sim
