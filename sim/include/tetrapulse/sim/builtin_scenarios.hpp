#pragma once
// The built-in scenarios: sim/scenarios/NAME.yaml, compiled into the program so
// that `tetrapulse sim NAME` works anywhere and `tetrapulse sim --print NAME`
// gives users a file to start from.
#include <string>
#include <vector>

namespace tetrapulse::sim {

struct BuiltinScenario {
  std::string name;
  std::string text;  // the YAML file, verbatim
};

// In name order.
const std::vector<BuiltinScenario>& builtin_scenarios();

// nullptr when there is no built-in of that name.
const BuiltinScenario* find_builtin_scenario(const std::string& name);

}  // namespace tetrapulse::sim
