// Issue 7's acceptance line: the paper's target and an optimised target
// (hardware/targets/) both localize. paper-exp1 (CI-sized) with its target's
// geometry taken from the file, codes and everything else unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenario_run.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::system_testing {
namespace {

class HardwareTargets : public ::testing::TestWithParam<const char*> {};

TEST_P(HardwareTargets, LocalizeInPaperExp1) {
  auto scenario = sim::load_scenario("paper-exp1");
  ASSERT_TRUE(scenario) << scenario.error().what();
  const auto file = read_targets_yaml(std::string(TETRAPULSE_SOURCE_DIR) + "/hardware/targets/" + GetParam());
  ASSERT_TRUE(file) << file.error().what();
  Target& target = scenario->targets.targets.at(0);
  target.marker_diameter_m = file->targets.at(0).marker_diameter_m;
  for (size_t m = 0; m < 4; ++m) target.markers[m].position_m = file->targets[0].markers[m].position_m;

  const auto run = run_scenario(*scenario, scenario->seed, scenario->frames.ci_count);
  ASSERT_TRUE(run) << run.error();
  const TargetEvaluation& all = run->evaluation.overall;
  std::printf("%s in paper-exp1: %zu poses, mean error %.2f mm / %.3f deg, coverage %.4f, misidentified %zu\n",
              GetParam(), all.rows, 1e3 * all.position_m.mean, all.orientation_rad.mean * 180 / M_PI, all.coverage(),
              all.misidentified);
  EXPECT_EQ(all.misidentified, 0u);
  EXPECT_GE(all.coverage(), 0.99);
  EXPECT_GT(all.visible_frames, 0u);
  EXPECT_LE(all.max_latency_frames, run->code_length_frames);
  EXPECT_LE(all.position_m.mean, 0.005);
  EXPECT_LE(all.orientation_rad.mean, 0.3 * M_PI / 180);
}

INSTANTIATE_TEST_SUITE_P(Files, HardwareTargets, ::testing::Values("paper-large.yaml", "optimised-4.yaml"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           std::string name = param.param;
                           for (char& c : name)
                             if (c == '-' || c == '.') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace tetrapulse::system_testing
