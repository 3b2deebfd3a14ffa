#include "demo_simulation.hpp"

#include "tetrapulse/host/sim_rig.hpp"

namespace tetrapulse::cli {

DemoSimulation virtual_rig_simulation() {
  return [](const sim::Scenario& scenario, const std::string& out, int64_t frames) -> DatasetResult<sim::SimulationSummary> {
    sim::SimulationOptions options;
    options.out = out;
    options.frames = frames;
    // The demo's boards are configured (Board::configure over SimLink) and synchronised
    // (GpioSync / CanSync) by the same host code that drives real boards.
    auto written = host::simulate_with_host_boards(scenario, options);
    if (!written) return dataset_error(out, 0, written.error().what());
    return *written;
  };
}

}  // namespace tetrapulse::cli
