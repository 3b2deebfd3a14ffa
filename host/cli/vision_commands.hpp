#pragma once
// The commands that need the vision libraries (OpenCV's image codecs and video
// input pull in some 250 shared libraries, 280 MB): they live in the program
// tetrapulse-vision beside tetrapulse, which hands them over (vision_forward.hpp).
// So board work on a robot (list, config, sync, flash...) starts in milliseconds
// and never loads them. One table names them for both programs' help.
#include <cstring>

namespace tetrapulse::cli {

struct VisionCommand {
  const char* name;
  const char* summary;
};

inline constexpr VisionCommand kVisionCommands[] = {
    {"sim", "Render a rig dataset (images, frames.csv, ground truth) from a scenario"},
    {"localize", "Identified 6D poses of the targets from images (poses.csv)"},
    {"eval", "Compare a poses file with its dataset's ground truth"},
    {"demo", "The virtual rig end to end: simulate, localize, evaluate, plot"},
    {"record", "A rig dataset from a live camera (Aravis or V4L2), stamped in rig time"},
};

// The summary of vision command `name` (nullptr: not one).
inline const char* vision_summary(const char* name) {
  for (const VisionCommand& c : kVisionCommands)
    if (std::strcmp(c.name, name) == 0) return c.summary;
  return nullptr;
}

}  // namespace tetrapulse::cli
