// Blobs that are not the whole image of one marker: a marker half past the
// image's border, two touching balls of one robot imaged as one blob and then
// parting. Each case is a built-in scenario on a seed other than its own, run
// past the moment that went wrong before (found by running every built-in
// scenario on new seeds, as an independently made recording would be).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <variant>

#include "scenario_run.hpp"
#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/sim/motion.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::system_testing {
namespace {

// crowd and crowd-on-off's first pair of drones where it flew before their first
// row was moved 30 px down the image (drone 1's top marker 18 px above it).
sim::Scenario first_row_at_the_top(sim::Scenario scenario) {
  for (size_t t = 0; t < scenario.targets.targets.size(); ++t) {
    const int id = scenario.targets.targets[t].id;
    auto* motion = std::get_if<sim::WaypointMotion>(&scenario.simulation[t].motion);
    if (!motion || (id != 1 && id != 2)) continue;
    for (sim::Waypoint& w : motion->points) w.pose.t.y() -= 30 * w.pose.t.z() / scenario.camera.fx;
  }
  return scenario;
}

ScenarioRun run_scenario_or_fail(const sim::Scenario& scenario, uint64_t seed, int64_t frames) {
  auto r = run_scenario(scenario, seed, frames);
  EXPECT_TRUE(r) << r.error();
  return r ? *r : ScenarioRun{};
}

TargetEvaluation run(const char* name, const std::vector<int>& ids, uint64_t seed, int64_t frames,
                     bool top_row = false) {
  auto scenario = sim::load_scenario(name);
  EXPECT_TRUE(scenario) << scenario.error().what();
  if (!scenario) return {};
  if (top_row) *scenario = first_row_at_the_top(*scenario);
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

// One of the paper's large targets near the right edge of a 752 x 480 view, 1.6 m
// below the camera, turned so that two of its balls line up along the view ray as it
// circles: from frame 44 their images touch and are one blob, from frame 75 one lies
// over the other. Seen as one blob, the pair is one observation of its light's
// centroid, (1 - s) h(marker) + s h(partner); with the two other markers that makes
// six equations for six unknowns, so an error in s goes straight into the pose.
// (The localizer's scale benchmark with eight targets lost this one in 41 of 120
// frames, and searched the whole image in 43.)
const char* kMergingPair = R"(name: merging-pair
frames: {start_ns: 4000000, period_ns: 10000000, exposure_ns: 2000000, count: 100000}
camera:
  image_width: 752
  image_height: 480
  hfov_deg: 90
  distortion_model: plumb_bob
  distortion_coefficients: [-0.05, 0.01, 0.0, 0.0, 0.0]
  psf_sigma_px: 0.6
  motion: {kind: static, position_m: [0.0, 0.0, 1.6], rpy_deg: [180, 0, 0]}
timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 10000000}
modulation: {kind: two_level, low: 0.3}
targets:
  - id: 8
    marker_diameter_m: 0.03
    radiance_e_per_ms: 1600
    markers:
      - position_m: [0.0, -0.1651, 0.2366]
        code: "011001100110"
      - position_m: [0.0, 0.1304, 0.1845]
        code: "010110100111"
      - position_m: [0.0626, -0.0221, 0.0539]
        code: "101010010110"
      - position_m: [-0.0802, 0.0249, 0.0621]
        code: "100110111001"
    motion: {kind: circle, center_m: [1.05, 0.35, 0.0], radius_m: 0.05, period_s: 6, rpy_deg: [0, 0, 270]}
)";

TEST(PartialBlobs, TwoBallsMergingIntoOneBlobShareItsLightAsTheirCodesAndOverlapSay) {
  // The pair's share s came from how the blob was split between the two predicted
  // markers, which swung from 0.02 to 0.98 between frames: poses missed the
  // prediction by 1-20 degrees and half of them were refused; on seeds 7 and 9 the
  // target was lost and identified wrongly three or four times (coverage 0.50-0.53,
  // up to 262 mm / 31 degrees off). s now comes from each ball's light before the
  // merge, its code's emission in this exposure and what the nearer ball hides of
  // the farther at the predicted pose (the share of its light, and where the part in
  // view is centred): on seeds 5, 7 and 9, 118 of 118 frames, at worst 2.1 mm / 0.35
  // degrees. (The virtual rig adds the balls' light where they overlap, real balls
  // hide each other: leaving the hiding out fits this rig better, 0.28 degrees at
  // worst, and would be wrong wherever a nearer ball hides a farther.)
  auto scenario = sim::parse_scenario(kMergingPair, "merging-pair");
  ASSERT_TRUE(scenario) << scenario.error().what();
  for (const uint64_t seed : {5, 7, 9}) {
    const ScenarioRun r = run_scenario_or_fail(*scenario, seed, 120);
    const TargetEvaluation& all = r.evaluation.overall;
    std::printf("merging-pair, seed %llu, 120 frames: %zu poses; mean error %.2f mm / %.3f deg; largest %.1f mm / "
                "%.2f deg; coverage %.4f (%zu of %zu); misidentified %zu\n",
                (unsigned long long)seed, all.rows, 1e3 * all.position_m.mean, all.orientation_rad.mean * 180 / M_PI,
                1e3 * all.position_m.max, all.orientation_rad.max * 180 / M_PI, all.coverage(), all.covered_frames,
                all.visible_frames, all.misidentified);
    EXPECT_EQ(all.misidentified, 0u) << "seed " << seed;
    EXPECT_GE(all.coverage(), 0.97) << "seed " << seed;
    EXPECT_LT(all.position_m.max, 0.004) << "seed " << seed;
    EXPECT_LT(all.orientation_rad.max, 1.0 * M_PI / 180) << "seed " << seed;
  }
}

TEST(PartialBlobs, AMarkerLeavingOverTheBorderIsNoMeasurementOfItsCentre) {
  // crowd, seed 41: drone 1's top marker rises past the image's top edge at frame
  // 27; what is left of its blob is a sliver on row 0, then a 2 x 5 px fragment
  // (rows 1-5) whose centroid lies 9 px from the marker's centre. Three markers
  // and that fragment gave a pose 357 mm off (misidentified), and the target was
  // then lost for 51 frames (coverage 81 %). A blob whose light reaches the border
  // and that no circle fit centred is now not a measurement (cut_by_border).
  const TargetEvaluation e = run("crowd", {1, 2}, 41, 40, /*top_row=*/true);
  EXPECT_EQ(e.misidentified, 0u);
  EXPECT_LT(e.position_m.max, 0.1);
}

TEST(PartialBlobs, ADroneWithOneMarkerAboveTheImageWaitsForItRatherThanGuess) {
  // crowd's drone 1 where the first row flew before: its top marker 18 px above
  // the image for 27 frames, its light wholly outside. With one code per drone
  // the codes cannot say which three are seen; P3P on its three blobs has an
  // exact root 179 degrees off whose own "missing" marker lies 40 px above the
  // image too (measured: localizer/ACCURACY.md). No pose can tell them apart, so
  // none is reported until the fourth marker's light reaches the image; then it
  // is identified within three frames, never wrongly.
  auto scenario = sim::load_scenario("crowd");
  ASSERT_TRUE(scenario) << scenario.error().what();
  const ScenarioRun r = run_scenario_or_fail(only_targets(first_row_at_the_top(*scenario), {1, 2}), scenario->seed, 40);
  const TargetEvaluation* drone = nullptr;
  for (const TargetEvaluation& t : r.evaluation.targets)
    if (t.target == 1) drone = &t;
  ASSERT_NE(drone, nullptr);
  // The first frame the top marker's disc (and its blur) reaches row 0.
  int64_t light_in = -1;
  const CameraModel camera(r.scenario.camera);
  const Target& target = r.scenario.targets.targets[0];
  for (const FrameRecord& f : r.frames) {
    const Pose pose = sim::Trajectory(r.scenario.simulation[0].motion, 0).at(1e-9 * double(f.timestamp_ns + f.exposure_ns / 2));
    const Eigen::Vector3d p = pose.apply(target.markers[1].position_m);
    Eigen::Vector2d px;
    ASSERT_TRUE(camera.project(p, &px));
    if (px.y() + camera.info().fx * target.marker_diameter_m / 2 / p.norm() + 1 >= 0) {
      light_in = f.frame;
      break;
    }
  }
  ASSERT_GT(light_in, 0) << "the top marker's light never reached the image: the case tests nothing";
  int64_t first = -1;
  for (const PoseRecord& p : r.poses)
    if (p.target == 1 && (first < 0 || p.frame < first)) first = p.frame;
  std::printf("drone 1, top marker above the image: its light reaches row 0 at frame %lld, first pose at %lld; "
              "largest error %.1f mm / %.2f deg; misidentified %zu\n",
              (long long)light_in, (long long)first, 1e3 * drone->position_m.max,
              drone->orientation_rad.max * 180 / M_PI, drone->misidentified);
  EXPECT_EQ(drone->misidentified, 0u);
  EXPECT_LT(drone->position_m.max, 0.05);
  EXPECT_LT(drone->orientation_rad.max, 3 * M_PI / 180);
  ASSERT_GE(first, 0) << "drone 1 never identified";
  EXPECT_LE(first, light_in + 3);
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
