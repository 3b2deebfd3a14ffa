// Blobs that are not the whole image of one marker: a marker half past the
// image's border, two touching balls of one robot imaged as one blob and then
// parting. Each case is a built-in scenario on a seed other than its own, run
// past the moment that went wrong before (found by running every built-in
// scenario on new seeds, as an independently made recording would be).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenario_run.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::system_testing {
namespace {

TargetEvaluation run(const char* name, const std::vector<int>& ids, uint64_t seed, int64_t frames) {
  auto scenario = sim::load_scenario(name);
  EXPECT_TRUE(scenario) << scenario.error().what();
  if (!scenario) return {};
  const auto r = run_scenario(only_targets(*scenario, ids), seed, frames);
  EXPECT_TRUE(r) << r.error();
  if (!r) return {};
  const TargetEvaluation& all = r->evaluation.overall;
  std::printf("%s, %zu targets, seed %llu, %lld frames: %zu poses; mean error %.2f mm / %.3f deg; largest %.1f mm / "
              "%.2f deg; coverage %.4f (%zu of %zu); misidentified %zu\n",
              name, ids.size(), (unsigned long long)seed, (long long)frames, all.rows, 1e3 * all.position_m.mean,
              all.orientation_rad.mean * 180 / M_PI, 1e3 * all.position_m.max, all.orientation_rad.max * 180 / M_PI,
              all.coverage(), all.covered_frames, all.visible_frames, all.misidentified);
  EXPECT_GT(all.visible_frames_total, 0u) << "nothing was visible: the case tests nothing";
  return all;
}

TEST(PartialBlobs, AMarkerLeavingOverTheBorderIsNoMeasurementOfItsCentre) {
  // crowd, seed 41: drone 1's top marker rises past the image's top edge at frame
  // 27; what is left of its blob is a sliver on row 0, then a 2 x 5 px fragment
  // (rows 1-5) whose centroid lies 9 px from the marker's centre. Three markers
  // and that fragment gave a pose 357 mm off (misidentified), and the target was
  // then lost for 51 frames (coverage 81 %). A blob whose light reaches the border
  // and that no circle fit centred is now not a measurement (cut_by_border).
  const TargetEvaluation e = run("crowd", {1, 2}, 41, 40);
  EXPECT_EQ(e.misidentified, 0u);
  EXPECT_LT(e.position_m.max, 0.1);
}

TEST(PartialBlobs, TwoTouchingBallsThatPartKeepTheirMarkers) {
  // climb-colour, seed 41: two balls of e-puck 2 image as one blob from frame 247
  // and part again from frame 269; the track of marker 0 followed marker 3's blob,
  // marker 3's blob went to a new unconfirmed track, and the three confirmed
  // markers fitted (exactly, as three always do) a pose that drifted 2 degrees a
  // frame: 26 rows up to 66 degrees and 99 mm off. A three-marker pose while a
  // fourth blob of the target is in sight now tries the assignments of the blobs
  // around it (marker_reassociation.hpp).
  const TargetEvaluation e = run("climb-colour", {2}, 41, 300);
  EXPECT_EQ(e.misidentified, 0u);
  EXPECT_LT(e.position_m.max, 0.05);
}

}  // namespace
}  // namespace tetrapulse::system_testing
