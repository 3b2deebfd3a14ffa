#pragma once
// Reading scenarios (sim/SCENARIOS.md). Every problem is reported as
// "FILE:LINE: FIELD: what is wrong" (DatasetError), the first one found; unknown
// fields are errors, so a misspelt field never silently takes its default.
#include <string>

#include "tetrapulse/datasets/dataset_error.hpp"
#include "tetrapulse/sim/scenario.hpp"

namespace tetrapulse::sim {

// `name` is how errors name the text (a path, or "NAME (built-in)").
DatasetResult<Scenario> parse_scenario(const std::string& text, const std::string& name);

// A built-in scenario's name, or a path to a YAML file.
DatasetResult<Scenario> load_scenario(const std::string& name_or_path);

}  // namespace tetrapulse::sim
