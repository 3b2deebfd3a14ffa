#pragma once
// The demo's simulation step: a scenario in, a rig dataset written to a folder.
// One function, so that the demo's boards can be driven another way (e.g.
// configured through the host's board code over a simulated link) without
// touching the rest of the demo.
#include <cstdint>
#include <functional>
#include <string>

#include "tetrapulse/datasets/dataset_error.hpp"
#include "tetrapulse/sim/dataset_simulation.hpp"
#include "tetrapulse/sim/scenario.hpp"

namespace tetrapulse::cli {

// Writes `frames` frame numbers of `scenario` (with its own seed) into the
// dataset folder `out` (created; it must not hold another dataset).
using DemoSimulation =
    std::function<DatasetResult<sim::SimulationSummary>(const sim::Scenario& scenario, const std::string& out,
                                                        int64_t frames)>;

// The virtual rig with simulated firmware boards in the loop, each configured and
// synchronised by the host's Board and sync master code over SimLink
// (host::simulate_with_host_boards; same files as `tetrapulse sim --host-boards`).
DemoSimulation virtual_rig_simulation();

}  // namespace tetrapulse::cli
