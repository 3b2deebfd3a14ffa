#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "tetrapulse/hardware/nelder_mead.hpp"

namespace tetrapulse::hardware {
namespace {

RC_GTEST_PROP(NelderMead, FindsTheTopOfAConcaveQuadratic, ()) {
  const int k = *rc::gen::inRange(1, 7);
  Eigen::VectorXd top(k), scale(k), x0(k);
  for (int i = 0; i < k; ++i) {
    top[i] = *rc::gen::inRange(-1000, 1001) * 1e-3;
    scale[i] = *rc::gen::inRange(1, 101) * 0.1;  // condition number up to 100
    x0[i] = *rc::gen::inRange(-1000, 1001) * 1e-3;
  }
  const Objective f = [&](const Eigen::VectorXd& x) { return -(scale.array() * (x - top).array().square()).sum(); };
  NelderMeadOptions o;
  o.step = 0.1;
  o.max_evaluations = 20000;
  const NelderMeadResult r = nelder_mead_maximize(f, x0, o);
  RC_ASSERT((r.x - top).cwiseAbs().maxCoeff() < 1e-6);
  RC_ASSERT(r.evaluations <= o.max_evaluations + k + 2);  // a shrink may finish past the budget
}

TEST(NelderMead, ClimbsRosenbrocksValley) {
  const Objective f = [](const Eigen::VectorXd& x) {
    return -(100 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1 - x[0], 2));
  };
  NelderMeadOptions o;
  o.step = 0.5;
  o.max_evaluations = 10000;
  const NelderMeadResult r = nelder_mead_maximize(f, Eigen::Vector2d(-1.2, 1.0), o);
  EXPECT_NEAR(r.x[0], 1.0, 1e-5);
  EXPECT_NEAR(r.x[1], 1.0, 1e-5);
}

TEST(NelderMead, NeverPrefersANaNOrLeavesAFeasibleRegionForAPenalty) {
  // Feasible only for x > 0, where the maximum sits on the boundary; NaN beyond x > 2.
  const Objective f = [](const Eigen::VectorXd& x) {
    if (x[0] > 2) return std::nan("");
    return x[0] > 0 ? 1.0 - x[0] : -10.0 + x[0];
  };
  NelderMeadOptions o;
  o.step = 0.3;
  const NelderMeadResult r = nelder_mead_maximize(f, Eigen::VectorXd::Constant(1, 1.5), o);
  EXPECT_GT(r.x[0], 0.0);
  EXPECT_LT(r.x[0], 1e-6);
  EXPECT_FALSE(std::isnan(r.f));
}

TEST(NelderMead, StopsAtTheEvaluationBudget) {
  int calls = 0;
  const Objective f = [&](const Eigen::VectorXd& x) {
    ++calls;
    return -x.squaredNorm() + std::sin(1e3 * x[0]);  // rough enough never to converge quickly
  };
  NelderMeadOptions o;
  o.max_evaluations = 300;
  o.x_tolerance = 0;
  o.f_tolerance = 0;
  const NelderMeadResult r = nelder_mead_maximize(f, Eigen::Vector3d(1, 2, 3), o);
  EXPECT_EQ(r.evaluations, calls);
  EXPECT_LE(calls, o.max_evaluations + 4);
  EXPECT_GE(r.f, f(Eigen::Vector3d(1, 2, 3)));
}

}  // namespace
}  // namespace tetrapulse::hardware
