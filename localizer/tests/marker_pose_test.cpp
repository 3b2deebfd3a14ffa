// A target's pose from its identified markers: four need no prediction, three
// need one (or stay unsolved), and a marker that does not fit is named.
#include "tetrapulse/localizer/marker_pose.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tetrapulse/localizer/testing/p3p_problems.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

struct View {
  Pose truth;
  std::array<Eigen::Vector2d, 4> pixels;
};

class MarkerPoseTest : public ::testing::Test {
 protected:
  // The target 0.7 m to `far` away.
  View view(double far = 2.5, double sigma_px = 0.1) {
    View v;
    v.truth = testing::random_visible_pose(rng, camera, target, 0.7, far, 10);
    v.pixels = testing::observe(rng, camera, target, v.truth, sigma_px);
    return v;
  }
  static std::vector<SeenMarker> seen(const View& v, std::initializer_list<int> markers) {
    std::vector<SeenMarker> out;
    for (int m : markers) out.push_back(SeenMarker{m, v.pixels[size_t(m)]});
    return out;
  }
  MarkerPoseOptions centres() const {
    MarkerPoseOptions o;
    o.sphere_centroid = false;  // observe() gives marker centres' projections
    return o;
  }

  std::mt19937_64 rng{17};
  CameraModel camera{testing::wide_plumb_bob_camera()};
  Target target = testing::hardware_target("paper-large.yaml");
};

TEST_F(MarkerPoseTest, FourMarkersNeedNoPrediction) {
  for (int trial = 0; trial < 200; ++trial) {
    const View v = view();
    const auto p = solve_marker_pose(camera, target, seen(v, {0, 1, 2, 3}), std::nullopt, centres());
    ASSERT_TRUE(p.has_value()) << trial;
    EXPECT_EQ(p->status, PoseStatus::kAllMarkers);
    EXPECT_EQ(p->used.size(), 4u);
    EXPECT_EQ(p->outlier, -1);
    EXPECT_LT(testing::pose_error(p->pose, v.truth), 0.03) << trial;  // 1.7 deg or 3 % of the distance
    EXPECT_LT(p->rms_px, 0.5);
    EXPECT_TRUE(p->has_covariance);
  }
}

TEST_F(MarkerPoseTest, ThreeMarkersWithoutAPredictionGiveNothing) {
  const View v = view();
  EXPECT_FALSE(solve_marker_pose(camera, target, seen(v, {0, 1, 3}), std::nullopt, centres()).has_value());
}

TEST_F(MarkerPoseTest, ThreeMarkersWithAPredictionAreNeverWrong) {
  // Predictions 1 degree and 1 cm off the truth: a pose is taken from P3P's
  // candidates only when it is clearly the one nearest the prediction, and then
  // it is the true one; most views give one.
  std::normal_distribution<double> n(0, 1);
  int solved = 0;
  constexpr int kTrials = 300;
  for (int trial = 0; trial < kTrials; ++trial) {
    const View v = view(1.5);
    Pose predicted = v.truth;
    predicted.R = so3_exp(0.0175 * Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized()) * predicted.R;
    predicted.t += 0.01 * Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    const int hidden = trial % 4;
    std::vector<SeenMarker> three;
    for (int m = 0; m < 4; ++m)
      if (m != hidden) three.push_back(SeenMarker{m, v.pixels[size_t(m)]});
    const auto p = solve_marker_pose(camera, target, three, predicted, centres());
    if (!p) continue;
    ++solved;
    EXPECT_EQ(p->status, PoseStatus::kThreeMarkers);
    // P3P's other poses lie tens of degrees away; noise moves the right one a few.
    EXPECT_LT(testing::pose_error(p->pose, v.truth), 0.08) << trial;
  }
  EXPECT_GE(solved, kTrials * 9 / 10);
}

TEST_F(MarkerPoseTest, ALitFourthMarkersLightPicksTheRootThePredictionWouldMiss) {
  // Three markers whose P3P has a wrong root near the truth, with the prediction
  // on that wrong root: by the prediction alone the wrong root is taken. The
  // fourth marker's code says it is lit, and a blob lies where the true root
  // puts it: that root is taken, refined with the blob as a fourth marker.
  std::normal_distribution<double> n(0, 1);
  int cases = 0, right = 0, wrong_without = 0;
  for (int trial = 0; trial < 3000 && cases < 40; ++trial) {
    const View v = view(2.0, 0.02);
    const int hidden = trial % 4;
    std::vector<SeenMarker> three;
    Bearing3 x;
    Point3x3 X;
    for (int m = 0; m < 4; ++m)
      if (m != hidden) three.push_back(SeenMarker{m, v.pixels[size_t(m)]});
    for (size_t i = 0; i < 3; ++i) {
      ASSERT_TRUE(camera.unproject(three[i].pixel, &x[i]));
      X[i] = target.markers[size_t(three[i].marker)].position_m;
    }
    PoseCandidates roots;
    const int k = solve_p3p(kDefaultP3PSolver, x, X, &roots);
    int wrong = -1;
    for (int r = 0; r < k; ++r) {
      const double d = pose_distance(roots[size_t(r)], v.truth);
      if (d > 0.05 && d < 0.25) wrong = r;
    }
    if (wrong < 0) continue;
    ++cases;
    const Pose predicted = roots[size_t(wrong)];
    const auto alone = solve_marker_pose(camera, target, three, predicted, centres());
    wrong_without += alone && testing::pose_error(alone->pose, v.truth) > 0.03;
    MarkerEvidence evidence;
    evidence.missing.push_back(MissingMarker{hidden, MarkerLight::kLit});
    evidence.lights.push_back(v.pixels[size_t(hidden)]);
    evidence.lights.push_back(v.pixels[size_t(hidden)] + Eigen::Vector2d(80, 60));  // another target's marker
    const auto p = solve_marker_pose(camera, target, three, predicted, centres(), evidence);
    if (p && testing::pose_error(p->pose, v.truth) < 0.01 && p->used.size() == 4) ++right;
  }
  ASSERT_GE(cases, 10);
  EXPECT_GE(wrong_without, cases / 2);  // the prediction alone takes the wrong root
  EXPECT_EQ(right, cases);
}

TEST_F(MarkerPoseTest, ABlobThatMayHoldTheLitFourthMarkerTooGivesNoPose) {
  // Two markers whose images touch (balls side by side, one behind the other): one
  // blob, its centroid between them, taken as one of three markers while the other
  // is "missing". Its code says it is lit, and the root puts it on that blob: the
  // three do not say where the target is, so no pose, even with the prediction on
  // the truth. Three markers whose lit fourth falls on no blob still give one.
  int merged = 0, refused = 0, clear = 0, solved = 0;
  for (int trial = 0; trial < 20000 && (merged < 20 || clear < 20); ++trial) {
    const View v = view(2.5, 0.02);
    const int hidden = trial % 4;
    int nearest = -1;
    for (int m = 0; m < 4; ++m)
      if (m != hidden && (nearest < 0 || (v.pixels[size_t(m)] - v.pixels[size_t(hidden)]).norm() <
                                             (v.pixels[size_t(nearest)] - v.pixels[size_t(hidden)]).norm()))
        nearest = m;
    const double apart = (v.pixels[size_t(nearest)] - v.pixels[size_t(hidden)]).norm();
    const double diameter_px = camera.info().fx * target.marker_diameter_m / v.truth.t.norm();
    MarkerEvidence evidence;
    evidence.missing.push_back(MissingMarker{hidden, MarkerLight::kLit});
    if (apart <= diameter_px && merged < 20) {
      std::vector<SeenMarker> three;
      for (int m = 0; m < 4; ++m)
        if (m != hidden)
          three.push_back(SeenMarker{m, m == nearest ? 0.5 * (v.pixels[size_t(m)] + v.pixels[size_t(hidden)])
                                                     : v.pixels[size_t(m)]});
      ++merged;
      refused += !solve_marker_pose(camera, target, three, v.truth, centres(), evidence);
    } else if (apart > 4 * diameter_px && clear < 20) {
      std::vector<SeenMarker> three;
      for (int m = 0; m < 4; ++m)
        if (m != hidden) three.push_back(SeenMarker{m, v.pixels[size_t(m)]});
      ++clear;
      const auto p = solve_marker_pose(camera, target, three, v.truth, centres(), evidence);
      solved += p && testing::pose_error(p->pose, v.truth) < 0.01;
    }
  }
  ASSERT_GE(merged, 10);
  ASSERT_GE(clear, 10);
  EXPECT_EQ(refused, merged);
  EXPECT_EQ(solved, clear);
}

TEST_F(MarkerPoseTest, AMarkerThatDoesNotFitIsNamedAndLeftOut) {
  // Near enough that the target spans well over 15 px (far away, four markers
  // 15 px off can be fitted by another pose: 8 equations, 6 unknowns).
  int named = 0;
  for (int trial = 0; trial < 100; ++trial) {
    View v = view(1.2);
    const int wrong = trial % 4;
    v.pixels[size_t(wrong)] += Eigen::Vector2d(12, -9);  // another light, 15 px off
    const auto p = solve_marker_pose(camera, target, seen(v, {0, 1, 2, 3}), v.truth, centres());
    if (!p || p->outlier != wrong) continue;
    ++named;
    EXPECT_LT(testing::pose_error(p->pose, v.truth), 0.03) << trial;
    EXPECT_EQ(p->used.size(), 3u);
  }
  // Not every view: in a few, another pose fits all four pixels within max_rms_px
  // (the localizer then relies on codes and the marker's track to drop it).
  EXPECT_GE(named, 90);
}

}  // namespace
}  // namespace tetrapulse
