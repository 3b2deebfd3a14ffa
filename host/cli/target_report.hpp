#pragma once
// What `tetrapulse target check` prints: the analysis of a targets.yaml
// (tetrapulse/hardware/target_analysis.hpp) as text for people or JSON for scripts.
#include <string>

#include "tetrapulse/hardware/target_analysis.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse::cli {

std::string format_target_check_text(const std::string& file, const TargetsFile& targets,
                                     const hardware::SystemAnalysis& analysis,
                                     const hardware::AnalysisSettings& settings);

std::string format_target_check_json(const std::string& file, const TargetsFile& targets,
                                     const hardware::SystemAnalysis& analysis,
                                     const hardware::AnalysisSettings& settings);

// "target 0: d01 = 0.300058 m > D2 = 0.3 m"
std::string describe_violation(const TargetsFile& targets, const hardware::Violation& v);

}  // namespace tetrapulse::cli
