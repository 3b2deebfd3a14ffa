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

// The light of target `index`'s board (its four markers as lights 0..3), given the whole
// scenario (targets, the board's clock and sync, the frames a GPIO strobe follows).
// contract_board_emitter plays the contract's formula (CodeEmitter); a simulated board
// running the firmware (firmware_board_emitter.hpp) plugs in here, the renderer
// unchanged. Occlusions are applied around whatever it returns.
using BoardEmitterFactory = std::function<std::unique_ptr<LedEmitter>(const Scenario& scenario, size_t index)>;
std::unique_ptr<LedEmitter> contract_board_emitter(const Scenario& scenario, size_t index);

// The firmware board emitter when the firmware core is part of the build, else the
// contract formula.
BoardEmitterFactory default_board_emitter();

Scene build_scene(const Scenario& scenario, uint64_t seed, const BoardEmitterFactory& board = default_board_emitter());

}  // namespace tetrapulse::sim
