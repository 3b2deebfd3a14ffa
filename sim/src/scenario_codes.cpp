#include "scenario_codes.hpp"

namespace tetrapulse::sim {

void apply_codebook(yaml_fields::Fields& fields, const YAML::Node& codebook, TargetsFile*) {
  // Not wired in yet: refuse rather than render markers with codes nobody chose.
  fields.fail(codebook,
              "codebook: codes from the codebook generator are not available yet; write each marker's code");
}

}  // namespace tetrapulse::sim
