#pragma once
// The accuracy table of `tetrapulse eval` and `tetrapulse demo`: text for people,
// JSON for scripts. Positions in mm, angles in degrees (reports only).
#include <string>

#include "tetrapulse/datasets/pose_evaluation.hpp"

namespace tetrapulse::cli {

// A table with one line per target and one for all, headed by `title`.
std::string evaluation_table(const Evaluation& e, const std::string& title);
// One Markdown table row for the whole run: | title | ... |.
std::string evaluation_markdown_header();
std::string evaluation_markdown_row(const Evaluation& e, const std::string& title);
std::string evaluation_json(const Evaluation& e);

}  // namespace tetrapulse::cli
