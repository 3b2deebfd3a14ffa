#include <gtest/gtest.h>

#include <cmath>

#include "tetrapulse/hardware/target_analysis.hpp"
#include "tetrapulse/hardware/top_view.hpp"

namespace tetrapulse::hardware {
namespace {

const Markers kPaperTarget{Eigen::Vector3d(0.0, -0.1651, 0.2366), Eigen::Vector3d(0.0, 0.1304, 0.1845),
                           Eigen::Vector3d(0.0626, -0.0221, 0.0539), Eigen::Vector3d(-0.0802, 0.0249, 0.0621)};

AnalysisSettings paper_analysis() {
  AnalysisSettings s;
  s.limits = Eq1Limits{};
  s.top_view = default_top_view_limits(s.limits);
  s.sphere = ViewSphere{1.0, 500};
  return s;
}

TEST(TargetAnalysis, ReportsThePapersTargetAsPublished) {
  const AnalysisSettings s = paper_analysis();
  ASSERT_FALSE(analysis_problem({kPaperTarget}, s));
  const SystemAnalysis a = analyse_targets({kPaperTarget}, {0.03}, s);
  ASSERT_EQ(a.targets.size(), 1u);
  // Six distances 15.06 .. 30.01 cm, about 3 cm apart: s_min just under the 3 cm bound.
  EXPECT_NEAR(a.shortest, 0.1506, 5e-5);
  EXPECT_NEAR(a.longest, 0.3001, 5e-5);
  EXPECT_GT(a.score.spread.s_min, 0.0298);
  EXPECT_LT(a.score.spread.s_min, 0.0300);
  EXPECT_EQ(a.score.spread.s_min, a.targets[0].spread.s_min);  // one target: the system is the target
  EXPECT_GE(a.targets[0].min_face_height, 0.12);
  EXPECT_GE(a.targets[0].min_triangle_altitude, a.targets[0].min_face_height);
  // Its coordinates are rounded to 0.1 mm: the longest distance ends 0.06 mm beyond D2.
  ASSERT_EQ(a.violations.size(), 1u);
  EXPECT_EQ(a.violations[0].quantity, "d01");
  EXPECT_TRUE(a.violations[0].above);
  EXPECT_NEAR(a.violations[0].value - 0.30, 5.8e-5, 1e-6);
  EXPECT_GT(a.score.violation, 0.0);
}

TEST(TargetAnalysis, MeasuresDegeneracy) {
  const double a = 0.2 / std::sqrt(8.0);
  const Markers regular{Eigen::Vector3d(a, a, a), Eigen::Vector3d(a, -a, -a), Eigen::Vector3d(-a, a, -a),
                        Eigen::Vector3d(-a, -a, a)};
  Markers squashed = regular;
  for (auto& p : squashed) p.z() *= 0.01;
  const AnalysisSettings s = paper_analysis();
  const SystemAnalysis r = analyse_targets({regular, squashed}, {0.01, 0.01}, s);
  EXPECT_NEAR(r.targets[0].volume_ratio, 1.0, 1e-12);
  EXPECT_NEAR(r.targets[0].flatness, 1.0, 1e-12);
  EXPECT_LT(r.targets[1].volume_ratio, 0.02);
  EXPECT_LT(r.targets[1].flatness, 0.02);
  EXPECT_GT(r.targets[1].conditioning.worst_kappa, r.targets[0].conditioning.worst_kappa);
}

TEST(TargetAnalysis, RejectsSettingsItCannotUse) {
  AnalysisSettings s = paper_analysis();
  s.sphere.distance = 0.2;  // inside the paper target's 0.375 m reach
  EXPECT_NE(analysis_problem({kPaperTarget}, s).value_or("").find("view distance"), std::string::npos);
  s = paper_analysis();
  s.sphere.views = 0;
  EXPECT_NE(analysis_problem({kPaperTarget}, s).value_or("").find("views"), std::string::npos);
  s = paper_analysis();
  Markers broken = kPaperTarget;
  broken[2].x() = NAN;
  EXPECT_NE(analysis_problem({broken}, s).value_or("").find("not finite"), std::string::npos);
  EXPECT_TRUE(analysis_problem({}, s));
}

}  // namespace
}  // namespace tetrapulse::hardware
