#pragma once
// Everything `tetrapulse target check` reports about a system of targets: Eq. 1 and
// its constraints (eq1_score.hpp), face heights (tetrahedron.hpp), how degenerate each
// target is, its top view (top_view.hpp) and its pose conditioning
// (pose_conditioning.hpp). Lengths in metres, target frames with z up.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/pose_conditioning.hpp"
#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

struct TargetAnalysis {
  Edges distances{};                     // d01 d02 d03 d12 d13 d23
  DistanceSpread spread;                 // over this target's six distances alone
  std::array<double, 4> face_heights{};  // h_k, marker k to the opposite face
  double min_face_height = 0;
  double min_triangle_altitude = 0;      // >= min_face_height
  double volume_ratio = 0;               // volume / regular tetrahedron's of equal RMS edge
  double flatness = 0;                   // sigma_3 / sigma_1 of the centred markers: 0 flat, 1 round
  TargetShape top_view;                  // projection along the target's z axis
  PoseConditioning conditioning;
};

// A constraint of Eq. 1 that does not hold.
struct Violation {
  int target = 0;          // index in the system
  std::string quantity;    // "d01", "h2", ...
  double value = 0;        // m
  double limit = 0;        // m
  bool above = false;      // value > limit (a distance above D2); else below
};

struct SystemAnalysis {
  std::vector<TargetAnalysis> targets;
  Eq1Score score;            // Eq. 1 under the limits
  Eq1Score top_score;        // Eq. 1 of the projections along each target's z, under the top-view limits
  double shortest = 0;       // over all distances
  double longest = 0;
  std::vector<Violation> violations;
};

struct AnalysisSettings {
  Eq1Limits limits;
  Eq1Limits top_view;
  ViewSphere sphere;
};

// What is wrong with the settings for these targets (naming the setting), or nullopt.
std::optional<std::string> analysis_problem(const std::vector<Markers>& targets, const AnalysisSettings& settings);

// Requires analysis_problem() == nullopt and one marker diameter (m) per target.
SystemAnalysis analyse_targets(const std::vector<Markers>& targets, const std::vector<double>& marker_diameters,
                               const AnalysisSettings& settings);

}  // namespace tetrapulse::hardware
