#pragma once
// The virtual rig end to end, for system tests: a scenario rendered into a rig
// dataset (a temporary folder, removed afterwards), localized frame by frame,
// evaluated against its ground truth, and compared with an oracle.
//
// The oracle is handed the true correspondences: in every frame it extracts
// blobs from the whole image (the localizer's own BlobExtractor, set up for the
// targets' appearance as the localizer's is), takes for each
// marker the blob nearest the marker's true projection (within max(3 px, the
// marker's image radius)), and solves cv::solvePnP on them (four markers:
// SOLVEPNP_SQPNP then solvePnPRefineLM; three: SOLVEPNP_ITERATIVE started at the
// true pose). Blob centroids are
// taken as the projections of the marker centres. Errors as pose_evaluation.hpp
// (metres, radians).
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/datasets/pose_evaluation.hpp"
#include "tetrapulse/sim/scenario.hpp"

namespace tetrapulse::system_testing {

struct PoseErrors {
  double position_m = 0;
  double orientation_rad = 0;
};

struct ScenarioRun {
  sim::Scenario scenario;
  std::vector<FrameRecord> frames;               // as written
  std::vector<PoseRecord> poses;                 // the localizer's
  Evaluation evaluation;
  // Per (frame, target id): errors of the localizer and of the oracle.
  std::map<std::pair<int64_t, int>, PoseErrors> localizer_errors, oracle_errors;
  // Frame period and the longest code in frames (0 for constant modulation).
  int64_t frame_period_ns = 0;
  int64_t code_length_frames = 0;
};

// Renders `scenario` with `seed` over `frames` frame numbers, localizes with
// `options`, evaluates and runs the oracle. Fails (a message) when the dataset
// cannot be written or read, or a frame is refused.
tl::expected<ScenarioRun, std::string> run_scenario(const sim::Scenario& scenario, uint64_t seed, int64_t frames,
                                                    const LocalizerOptions& options = {});

// `scenario` with only the targets whose id is in `ids` (their markers and how
// they are simulated), in the scenario's order.
sim::Scenario only_targets(sim::Scenario scenario, const std::vector<int>& ids);

// Mean errors of the localizer and the oracle over the (frame, target) pairs both reported.
struct OracleComparison {
  size_t pairs = 0;
  PoseErrors localizer, oracle;
};
OracleComparison compare_with_oracle(const ScenarioRun& run);

}  // namespace tetrapulse::system_testing
