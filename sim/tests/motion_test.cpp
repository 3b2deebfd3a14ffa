// Trajectories: each kind does what its header says.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "tetrapulse/sim/motion.hpp"

namespace tetrapulse::sim {
namespace {

constexpr double kDeg = M_PI / 180;

Pose pose(double x, double y, double z, double yaw_deg) {
  return Pose{rotation_from_rpy(Eigen::Vector3d(0, 0, yaw_deg * kDeg)), Eigen::Vector3d(x, y, z)};
}

TEST(Motion, RpyIsZyx) {
  // Yaw 90: x to y. Roll 180 (a camera looking down): z to -z, y to -y.
  EXPECT_LT((rotation_from_rpy({0, 0, M_PI / 2}) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((rotation_from_rpy({M_PI, 0, 0}) * Eigen::Vector3d::UnitZ() + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  const Eigen::Vector3d rpy(0.3, -0.2, 1.1);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())).toRotationMatrix();
  EXPECT_LT((rotation_from_rpy(rpy) - expected).norm(), 1e-12);
}

TEST(Motion, WaypointsInterpolateAndHoldOrLoop) {
  WaypointMotion m;
  m.points = {{0.0, pose(0, 0, 0, 0)}, {2.0, pose(2, 0, 0, 90)}, {4.0, pose(2, 2, 0, 90)}};
  const Trajectory still(m, 1);
  EXPECT_LT((still.at(1.0).t - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(rotation_angle_between(still.at(1.0).R, pose(0, 0, 0, 45).R), 0.0, 1e-12);
  EXPECT_LT((still.at(3.0).t - Eigen::Vector3d(2, 1, 0)).norm(), 1e-12);
  EXPECT_LT((still.at(-5).t - Eigen::Vector3d(0, 0, 0)).norm(), 1e-12);
  EXPECT_LT((still.at(9).t - Eigen::Vector3d(2, 2, 0)).norm(), 1e-12);
  m.loop = true;
  const Trajectory looped(m, 1);
  EXPECT_LT((looped.at(5.0).t - still.at(1.0).t).norm(), 1e-12);
  EXPECT_LT((looped.at(-1.0).t - still.at(3.0).t).norm(), 1e-12);
}

TEST(Motion, CircleKeepsItsRadiusPlaneAndPeriod) {
  CircleMotion c;
  c.center_m = {0.5, -0.2, 1.0};
  c.radius_m = 0.3;
  c.period_s = 4;
  c.axis = Eigen::Vector3d(0, 1, 1).normalized();
  const Trajectory t(c, 1);
  for (double s = 0; s < 8; s += 0.37) {
    const Pose p = t.at(s);
    EXPECT_NEAR((p.t - c.center_m).norm(), 0.3, 1e-12);
    EXPECT_NEAR((p.t - c.center_m).dot(c.axis), 0.0, 1e-12);
    EXPECT_LT((t.at(s + 4).t - p.t).norm(), 1e-12);
    // Following the tangent, the body turns with the angle travelled.
    EXPECT_NEAR(rotation_angle_between(p.R, t.at(s + 1).R), M_PI / 2, 1e-9);
  }
}

RC_GTEST_PROP(Motion, SmoothRandomStaysWithinItsAmplitudesAndIsSmooth, ()) {
  SmoothRandomMotion m;
  m.centre = pose(0.1, 0.2, 1.2, 30);
  m.amplitude_m = {*rc::gen::inRange(0, 100) / 100.0, *rc::gen::inRange(0, 100) / 100.0, 0.53};
  m.rotation_amplitude_rad = Eigen::Vector3d(12, 12, 60) * kDeg;
  m.min_period_s = *rc::gen::inRange(5, 50) / 10.0;
  const uint64_t seed = *rc::gen::arbitrary<uint64_t>();
  const Trajectory t(m, seed), same(m, seed), other(m, seed + 1);
  const double max_speed = 2 * M_PI / m.min_period_s * m.amplitude_m.norm();
  bool differs = false;
  Pose prev = t.at(0);
  for (double s = 0.01; s < 20; s += 0.01) {
    const Pose p = t.at(s);
    const Eigen::Vector3d d = p.t - m.centre.t;
    for (int i = 0; i < 3; ++i) RC_ASSERT(std::abs(d[i]) <= m.amplitude_m[i] + 1e-12);
    RC_ASSERT(rotation_angle_between(p.R, m.centre.R) <= m.rotation_amplitude_rad.norm() + 1e-9);
    RC_ASSERT((p.t - prev.t).norm() <= max_speed * 0.01 + 1e-12);
    RC_ASSERT((same.at(s).t - p.t).norm() == 0.0);
    differs = differs || (other.at(s).t - p.t).norm() > 1e-6;
    prev = p;
  }
  RC_ASSERT(differs || m.amplitude_m.norm() < 1e-9);
}

}  // namespace
}  // namespace tetrapulse::sim
