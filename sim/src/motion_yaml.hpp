#pragma once
// The `motion:` block of a scenario (camera, target or distractor); sim/SCENARIOS.md.
#include <string>

#include "tetrapulse/datasets/yaml_fields.hpp"
#include "tetrapulse/sim/motion.hpp"

namespace tetrapulse::sim {

MotionSpec read_motion(yaml_fields::Fields& fields, const YAML::Node& node, const std::string& path);

}  // namespace tetrapulse::sim
