#pragma once
// Where a scenario's codes come from. Today every code is written out in the
// scenario (markers[].code, as in targets.yaml). The `codebook:` section is the
// place for codes drawn from the project's codebook generator once it exists: it
// will fill in the codes of markers that have none.
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/datasets/yaml_fields.hpp"

namespace tetrapulse::sim {

void apply_codebook(yaml_fields::Fields& fields, const YAML::Node& codebook, TargetsFile* targets);

}  // namespace tetrapulse::sim
