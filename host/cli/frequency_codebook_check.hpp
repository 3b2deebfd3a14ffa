#pragma once
// `tetrapulse codebook check` of a file's frequency codes (square waves, protocol/SPEC.md
// §8.5) at one camera, and of its binary codes beside them: what codebook_check_command.cpp
// hands over once it has sorted a file's codes by family.
#include <string>
#include <vector>

#include "frequency_codebook_command.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse::cli {

// One code of a targets.yaml and how the check names it ("targets[0] (id 1) marker 2").
struct LabelledCode {
  Code code;
  std::string label;
};

// The square waves by protocol::check_frequency_codes (every code, every pair) on the file's
// bit period, and every binary code by protocol::check_binary_beside_frequency. Faults go to
// stderr one per line, a pass to stdout as one line; returns the exit code. `what` names the
// codes ("8 frequency codes (one per target)").
int check_frequency_family(const std::string& path, const TargetsFile& file, const FrequencyCodebookArgs& camera,
                           const std::vector<LabelledCode>& frequency, const std::vector<LabelledCode>& binary,
                           const std::string& what);

}  // namespace tetrapulse::cli
