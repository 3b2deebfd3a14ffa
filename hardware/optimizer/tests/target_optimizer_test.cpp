#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tetrapulse/hardware/target_analysis.hpp"
#include "tetrapulse/hardware/target_optimizer.hpp"
#include "tetrapulse/hardware/top_view.hpp"

namespace tetrapulse::hardware {
namespace {

// The paper's large target and parameters (Breitenmoser et al. 2011, Sec. III-A).
const Markers kPaperTarget{Eigen::Vector3d(0.0, -0.1651, 0.2366), Eigen::Vector3d(0.0, 0.1304, 0.1845),
                           Eigen::Vector3d(0.0626, -0.0221, 0.0539), Eigen::Vector3d(-0.0802, 0.0249, 0.0621)};

OptimizerSettings paper_settings(int targets, int restarts, uint64_t seed) {
  OptimizerSettings s;
  s.targets = targets;
  s.limits = Eq1Limits{0.15, 0.30, 0.12, default_weight(6 * targets)};
  s.top_view = default_top_view_limits(s.limits);
  s.restarts = restarts;
  s.seed = seed;
  s.threads = 2;
  return s;
}

std::vector<TargetShape> shapes_of(const std::vector<Markers>& targets) {
  std::vector<TargetShape> shapes;
  for (const Markers& m : targets) shapes.push_back(solid_shape(edges_of(m)));
  return shapes;
}

TEST(TargetOptimizer, BeatsThePaperTargetWithThePapersParameters) {
  const OptimizerSettings s = paper_settings(1, 200, 1);
  const auto result = optimize_targets(s);
  ASSERT_TRUE(result);
  const double paper_s_min = eq1_score({solid_shape(edges_of(kPaperTarget))}, s.limits).spread.s_min;
  const Eq1Score score = eq1_score(shapes_of(result->targets), s.limits);
  EXPECT_EQ(score.violation, 0.0);  // every distance in [D1, D2], every face height >= H
  EXPECT_GE(score.spread.s_min, paper_s_min);
  EXPECT_LE(score.spread.s_min, (s.limits.d2 - s.limits.d1) / 5 + 1e-12);  // six distances can do no better
  EXPECT_NEAR(score.f, result->score.f, 1e-15);
}

TEST(TargetOptimizer, SameSeedGivesTheSameTargetsOnAnyThreadCount) {
  OptimizerSettings s = paper_settings(2, 24, 42);
  s.threads = 1;
  const auto one = optimize_targets(s);
  s.threads = 3;
  const auto three = optimize_targets(s);
  ASSERT_TRUE(one && three);
  ASSERT_EQ(one->targets.size(), 2u);
  EXPECT_EQ(one->restart, three->restart);
  for (size_t t = 0; t < 2; ++t) {
    for (int k = 0; k < 4; ++k) EXPECT_EQ(one->targets[t][k], three->targets[t][k]);  // bit for bit
  }
  s.seed = 43;
  const RestartResult other = optimize_restart(s, 0);
  s.seed = 42;
  EXPECT_NE(other.edges[0], optimize_restart(s, 0).edges[0]);  // the seed matters
}

TEST(TargetOptimizer, EightTargetsJointlyBeatEightOptimisedAlone) {
  const Eq1Limits system_limits{0.15, 0.30, 0.12, default_weight(48)};
  std::vector<Markers> alone;
  for (uint64_t seed = 1; seed <= 8; ++seed) alone.push_back(optimize_targets(paper_settings(1, 20, seed))->targets[0]);
  const auto joint = optimize_targets(paper_settings(8, 4, 1));
  ASSERT_TRUE(joint);
  const Eq1Score alone_score = eq1_score(shapes_of(alone), system_limits);
  const Eq1Score joint_score = eq1_score(shapes_of(joint->targets), system_limits);
  std::printf("[measure] 8 targets: system-wide s_min %.3f mm jointly, %.4f mm for 8 optimised alone\n",
              1e3 * joint_score.spread.s_min, 1e3 * alone_score.spread.s_min);
  EXPECT_EQ(joint_score.violation, 0.0);
  EXPECT_EQ(alone_score.violation, 0.0);
  // Alone, every target finds the same distance set {D1, D1 + 3 cm, ..., D2}, so the system's
  // s_min is what separates near-equal optima; jointly the 48 distances spread out.
  EXPECT_GT(joint_score.spread.s_min, 10 * alone_score.spread.s_min);
  EXPECT_GT(joint_score.spread.s_min, 0.9 * (0.30 - 0.15) / 47);  // the bound for 48 distances
  EXPECT_LE(joint_score.spread.s_min, (0.30 - 0.15) / 47 + 1e-12);
}

TEST(TargetOptimizer, ReportsWhenNoRestartMeetsTheConstraints) {
  OptimizerSettings s = paper_settings(1, 8, 1);
  s.limits.h = 0.28;  // taller than any tetrahedron with edges <= 0.30 m
  const auto result = optimize_targets(s);
  ASSERT_TRUE(result);
  EXPECT_GT(result->score.violation, 0.0);
  EXPECT_LT(result->score.f, 0.0);
}

TEST(TargetOptimizer, PlacesTargetsOnTheSupportPlane) {
  OptimizerSettings s = paper_settings(3, 6, 5);
  s.lift = 0.02;
  const auto result = optimize_targets(s);
  ASSERT_TRUE(result);
  for (const Markers& m : result->targets) {
    double z_min = INFINITY;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : m) {
      z_min = std::min(z_min, p.z());
      centroid += p / 4;
    }
    EXPECT_NEAR(z_min, 0.02, 1e-12);
    EXPECT_NEAR(centroid.x(), 0.0, 1e-12);
    EXPECT_NEAR(centroid.y(), 0.0, 1e-12);
    EXPECT_NEAR(m[1].x() - m[0].x(), 0.0, 1e-12);  // marker 0 -> 1 seen from above runs along +y
    EXPECT_GT(m[1].y() - m[0].y(), 0.0);
  }
  // The top-view score is that of the file's z axis.
  const std::vector<TargetShape> top =
      top_view_shapes(result->targets, std::vector<Eigen::Vector3d>(3, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(eq1_score(top, s.top_view).f, result->top_score.f, 1e-15);
}

TEST(TopView, TurnsThePaperTargetAtLeastAsWellAsAnyScannedDirection) {
  const Eq1Limits top = default_top_view_limits(Eq1Limits{});
  const TopView view = best_top_view({kPaperTarget}, top);
  ASSERT_EQ(view.up.size(), 1u);
  EXPECT_NEAR(view.up[0].norm(), 1.0, 1e-12);
  // Directions the optimiser did not scan (500 of them, both hemispheres).
  for (int i = 0; i < 500; ++i) {
    const double z = 1 - (i + 0.37) / 250.0, r = std::sqrt(1 - z * z), phi = 2.1 * i;
    const Eigen::Vector3d up(r * std::cos(phi), r * std::sin(phi), z);
    EXPECT_GE(view.score.f + 1e-9, eq1_score(top_view_shapes({kPaperTarget}, {up}), top).f) << i;
  }
}

TEST(TargetOptimizer, RejectsUnusableSettingsByName) {
  const auto problem = [](auto change) {
    OptimizerSettings s = paper_settings(1, 10, 1);
    change(s);
    return settings_problem(s).value_or("");
  };
  EXPECT_EQ(problem([](OptimizerSettings&) {}), "");
  EXPECT_NE(problem([](OptimizerSettings& s) { s.limits.d1 = 0.4; }).find("d2 must be greater than d1"),
            std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.limits.d1 = -0.1; }).find("d1"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.limits.h = 0.5; }).find("h must"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.limits.w = 1.5; }).find("w must"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.limits.d2 = NAN; }).find("d2"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.top_view.d2 = 0.01; }).find("top-d2"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.targets = 0; }).find("targets"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.restarts = 0; }).find("restarts"), std::string::npos);
  EXPECT_NE(problem([](OptimizerSettings& s) { s.threads = 0; }).find("threads"), std::string::npos);
  OptimizerSettings bad = paper_settings(1, 10, 1);
  bad.limits.d1 = 0.5;
  EXPECT_FALSE(optimize_targets(bad));
}

}  // namespace
}  // namespace tetrapulse::hardware
