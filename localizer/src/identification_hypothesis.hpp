#pragma once
// Internal to TargetIdentifier (target_identifier.cpp, target_identifier_edge.cpp,
// target_identifier_enumeration.cpp):
// a hypothesis and the code evidence of each candidate track.
#include <array>
#include <limits>
#include <vector>

#include "tetrapulse/localizer/target_identifier.hpp"

namespace tetrapulse {

struct TargetIdentifier::TrackCodes {
  size_t from = 0;                              // first sample used
  std::vector<CodeMatch> matches;               // synchronized: one per code
  std::vector<std::vector<CodeMatch>> phases;   // free-running: per code, per phase
  std::vector<double> best_cost;                // per code (over phases when free-running)
};

struct TargetIdentifier::Hypothesis {
  size_t target = 0;
  std::array<int, 4> track{};  // index into the candidate tracks; -1: the marker out of view
  // A set of four tracks for a target whose markers the codes cannot tell apart
  // (all play one code): geometry assigns them to markers.
  bool unordered = false;
  int missing = -1;            // three-track hypotheses: the marker out of view (0..3)
  double cost = 0;
  CodeMatch codes;
  int phase = 0;               // free-running: phase index of the target's clock
  // Free-running: the best cost at a phase more than a bit away from the best
  // ones (another alignment of the codes: a cyclic shift).
  double shifted_cost = std::numeric_limits<double>::infinity();
  int8_t geometry_state = 0;   // 0 not evaluated, 1 holds, -1 fails
  Pose pose;
  double rms_px = std::numeric_limits<double>::infinity();
  int out_of_view_poses = 0;   // three-track hypotheses: P3P roots that put `missing` out of view

  bool shares(const Hypothesis& o) const {
    if (target == o.target) return true;
    for (int a : track)
      for (int b : o.track)
        if (a >= 0 && a == b) return true;
    return false;
  }
};

}  // namespace tetrapulse
