#pragma once
// Target geometry optimisation, Breitenmoser, Kneip & Siegwart 2011, Sec. III-A:
//   maximise Eq. 1 (eq1_score.hpp) over the shapes of n four-marker targets,
// by Nelder-Mead from `restarts` random starts whose edge lengths are drawn from a
// discrete grid in [D1, D2]; then, among the restarts whose Eq. 1 is within
// kSelectTolerance of the best (the paper's "several best solutions"), the one that is
// most distinct seen from the top after the top-view rotation (top_view.hpp).
//
// A target's parameters are its six edge lengths: Eq. 1 depends on nothing else, and
// a rigid motion of the markers would add six directions the simplex cannot improve.
// Several targets are optimised jointly (block_ascent: one target at a time against
// the system's Eq. 1). Restarts run in parallel; restart i draws from
// SeededStream(seed, i) alone, so a seed gives the same targets for any thread count.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

struct OptimizerSettings {
  int targets = 1;              // n, 1 .. kMaxTargets
  Eq1Limits limits;             // D1, D2, H, w (m)
  Eq1Limits top_view;           // adjusted constraints of the top-view step (default_top_view_limits)
  int restarts = 1000;          // random starts
  uint64_t seed = 1;
  int threads = 1;              // worker threads; results do not depend on it
  int grid_levels = 16;         // starting edge lengths: D1 + i (D2 - D1) / (levels - 1), i < levels
  double lift = 0.03;           // lowest marker centre above the support plane z = 0 (m)
};

constexpr int kMaxTargets = 64;
constexpr int kMaxRestarts = 1'000'000;
constexpr int kMaxThreads = 256;
constexpr double kSelectTolerance = 1e-3;  // relative, on Eq. 1's f

struct OptimizedTargets {
  std::vector<Markers> targets;  // target frames: z up, support plane z = 0 (top_view.hpp)
  Eq1Score score;                // Eq. 1 of the targets
  Eq1Score top_score;            // Eq. 1 of their top-view projections under settings.top_view
  int restart = 0;               // the restart they come from
  int candidates = 0;            // restarts that went through the top-view selection
};

// What is wrong with the settings (naming the setting), or nullopt when they are usable.
std::optional<std::string> settings_problem(const OptimizerSettings& settings);

// nullopt exactly when settings_problem() reports a problem.
std::optional<OptimizedTargets> optimize_targets(const OptimizerSettings& settings);

// One restart of the shape stage (before the top-view step): the edges of every target.
struct RestartResult {
  std::vector<Edges> edges;
  Eq1Score score;
};
RestartResult optimize_restart(const OptimizerSettings& settings, int index);

}  // namespace tetrapulse::hardware
