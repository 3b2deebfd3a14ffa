// Motion the prediction cannot follow, in frames whose markers are dark: a robot
// that stops and turns in place, a drone that stops short. Piecewise-linear paths
// (waypoints) change velocity within one frame, as an independently scripted
// recording may; the constant-velocity extrapolation then overshoots for as long
// as the markers stay dark. Each case is one target of a built-in scenario, run
// past the moment its motion changes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenario_run.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::system_testing {
namespace {

TargetEvaluation run_alone(const char* name, int id, int64_t frames) {
  auto scenario = sim::load_scenario(name);
  EXPECT_TRUE(scenario) << scenario.error().what();
  if (!scenario) return {};
  const auto run = run_scenario(only_targets(*scenario, {id}), scenario->seed, frames);
  EXPECT_TRUE(run) << run.error();
  if (!run) return {};
  const TargetEvaluation& all = run->evaluation.overall;
  std::printf("%s, target %d alone, %lld frames: %zu poses; mean error %.2f mm / %.3f deg; coverage %.4f (%zu of %zu); "
              "misidentified %zu\n",
              name, id, (long long)frames, all.rows, 1e3 * all.position_m.mean, all.orientation_rad.mean * 180 / M_PI,
              all.coverage(), all.covered_frames, all.visible_frames, all.misidentified);
  EXPECT_GT(all.visible_frames_total, 0u) << "the target was never visible: the case tests nothing";
  return all;
}

TEST(AbruptMotion, AGroundRobotThatStopsAndTurnsInPlaceWhileDarkKeepsItsPose) {
  // swarm's robot 3 drives at 0.12 m/s, stops at 3.5 s (frame 105) and turns 90
  // degrees in 0.5 s; its on_off markers leave three lit in the frames after. The
  // three-marker poses lie 0.14-0.77 rad from the straight-on extrapolation; the
  // dark marker's own track picks their root (was: refused, 7 frames without a pose).
  const TargetEvaluation e = run_alone("swarm", 3, 125);
  EXPECT_EQ(e.misidentified, 0u);
  EXPECT_GE(e.coverage(), 0.99);
}

TEST(AbruptMotion, ADroneThatStopsShortWhileDarkIsNeverReportedWrong) {
  // crowd-on-off's drone 17 flies at 3 m/s, 6 m away, and stops dead at 0.6 s
  // (frame 60) with its markers dark for two frames: every track overshoots its
  // blob by 14 px, and one takes the blob of the marker beside it. The three
  // others' P3P roots then lie 0.6 rad from the prediction, and the gate, grown
  // with the frames since the last pose, let one through at frame 67: reported
  // for the next 530 frames, 1 m and 36 degrees off. Now its four blobs are
  // fitted afresh in frame 63 (marker_reassociation.hpp) and the tracks take
  // their own blobs back.
  const TargetEvaluation e = run_alone("crowd-on-off", 17, 100);
  EXPECT_EQ(e.misidentified, 0u);
  EXPECT_LT(e.position_m.max, 0.05);
  EXPECT_GE(e.coverage(), 0.99);
}

TEST(AbruptMotion, ADroneLostAtItsStopBesideAnothersMarkerIsFoundAgainAndPosedWell) {
  // crowd-on-off's drone 1 stops at 0.6 s (frame 60) 2.3 m away with its marker 0
  // 11 px from drone 6's marker 3 (4.9 m away, stopped too); their blobs touch.
  // Lost at the stop, it was never identified again: in every frame drone 6's
  // marker was dark, drone 6's track took drone 1's marker blob from outside its
  // window, so that marker never had a track of its own (0 poses after frame 59).
  // Once found, its identifying fit (0.58 px, the other's light pulling the
  // marker) stood for its noise and let poses 35 mm off through.
  auto scenario = sim::load_scenario("crowd-on-off");
  ASSERT_TRUE(scenario) << scenario.error().what();
  const auto run = run_scenario(*scenario, scenario->seed, 100);
  ASSERT_TRUE(run) << run.error();
  ASSERT_EQ(run->evaluation.targets.size(), 32u);
  const TargetEvaluation& drone1 = run->evaluation.targets[0];
  std::printf("crowd-on-off, 100 frames: drone 1 %zu poses, coverage %.4f (%zu of %zu), largest %.1f mm, "
              "misidentified %zu; all %.4f\n",
              drone1.rows, drone1.coverage(), drone1.covered_frames, drone1.visible_frames, 1e3 * drone1.position_m.max,
              drone1.misidentified, run->evaluation.overall.coverage());
  EXPECT_EQ(run->evaluation.overall.misidentified, 0u);
  EXPECT_GE(drone1.coverage(), 0.7);  // 0.58 when never found again, 0.74 now
  EXPECT_LT(drone1.position_m.max, 0.01);  // 34.7 mm with the identifying fit for its noise
  EXPECT_GE(run->evaluation.overall.coverage(), 0.99);
}

}  // namespace
}  // namespace tetrapulse::system_testing
