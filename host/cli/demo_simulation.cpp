#include "demo_simulation.hpp"

namespace tetrapulse::cli {

DemoSimulation virtual_rig_simulation() {
  return [](const sim::Scenario& scenario, const std::string& out, int64_t frames) {
    sim::SimulationOptions options;
    options.out = out;
    options.frames = frames;
    return sim::simulate_dataset(scenario, options);
  };
}

}  // namespace tetrapulse::cli
