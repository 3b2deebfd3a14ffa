// Pose prediction: the paper's linear regression over k_R poses and the
// constant-velocity Kalman filter, on motions whose future is known.
#include "tetrapulse/localizer/pose_predictor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tetrapulse {
namespace {

constexpr int64_t kFrameNs = 10'000'000;

// A target moving at constant velocity and spinning at a constant rate.
Pose uniform_motion(int64_t t_ns) {
  const double t = double(t_ns) * 1e-9;
  const Eigen::Vector3d v(0.3, -0.2, 0.5), w(0.4, -1.1, 2.0);  // m/s, rad/s
  const Eigen::Matrix3d R0 = so3_exp(Eigen::Vector3d(0.3, 0.2, -0.1));
  return Pose{so3_exp(w * t) * R0, Eigen::Vector3d(0.1, 0.0, 1.2) + v * t};
}

double position_error(const Pose& a, const Pose& b) { return (a.t - b.t).norm(); }
double angle_error(const Pose& a, const Pose& b) { return rotation_angle_between(a.R, b.R); }

TEST(PosePredictor, NothingToPredictWithoutHistory) {
  PosePredictor p;
  EXPECT_FALSE(p.predict(0).has_value());
}

TEST(PosePredictor, OnePoseIsHeld) {
  PosePredictor p;
  p.add(0, uniform_motion(0));
  const auto q = p.predict(kFrameNs);
  ASSERT_TRUE(q.has_value());
  EXPECT_LT(position_error(*q, uniform_motion(0)), 1e-12);
}

TEST(PosePredictor, TwoPoseRegressionExtrapolatesUniformMotionExactly) {
  PosePredictor p;  // k_R = 2, the paper's default
  p.add(0, uniform_motion(0));
  p.add(kFrameNs, uniform_motion(kFrameNs));
  for (int64_t ahead : {1, 2, 5}) {
    const int64_t t = kFrameNs + ahead * kFrameNs;
    const auto q = p.predict(t);
    ASSERT_TRUE(q.has_value());
    EXPECT_LT(position_error(*q, uniform_motion(t)), 1e-9) << ahead;
    EXPECT_LT(angle_error(*q, uniform_motion(t)), 1e-9) << ahead;
  }
}

TEST(PosePredictor, LongerRegressionAveragesNoiseAway) {
  // Noisy poses of a uniform motion: k_R = 8 predicts better than k_R = 2 on average.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 1);
  PredictionOptions eight;
  eight.regression_poses = 8;
  double error2 = 0, error8 = 0;
  for (int trial = 0; trial < 200; ++trial) {
    PosePredictor p2, p8(eight);
    for (int k = 0; k < 8; ++k) {
      const int64_t t = int64_t(trial * 100 + k) * kFrameNs;
      Pose noisy = uniform_motion(t);
      noisy.t += 0.001 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      noisy.R = so3_exp(0.002 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng))) * noisy.R;
      p2.add(t, noisy);
      p8.add(t, noisy);
    }
    const int64_t next = int64_t(trial * 100 + 8) * kFrameNs;
    error2 += position_error(*p2.predict(next), uniform_motion(next));
    error8 += position_error(*p8.predict(next), uniform_motion(next));
  }
  EXPECT_LT(error8, 0.5 * error2);
}

TEST(PosePredictor, KalmanFilterLearnsUniformMotion) {
  PredictionOptions kalman;
  kalman.model = PredictionModel::kConstantVelocity;
  PosePredictor p(kalman);
  for (int k = 0; k < 30; ++k) p.add(k * kFrameNs, uniform_motion(k * kFrameNs), 1e-4, 1e-4);
  const int64_t next = 31 * kFrameNs;
  const auto q = p.predict(next);
  ASSERT_TRUE(q.has_value());
  // A frame and a half ahead, a few tenths of a millimetre and degree off at most.
  EXPECT_LT(position_error(*q, uniform_motion(next)), 3e-4);
  EXPECT_LT(angle_error(*q, uniform_motion(next)), 5e-3);
}

TEST(PosePredictor, NoPredictionLongAfterTheLastPose) {
  PredictionOptions options;
  options.max_extrapolation_ns = 100'000'000;
  PosePredictor p(options);
  p.add(0, uniform_motion(0));
  p.add(kFrameNs, uniform_motion(kFrameNs));
  EXPECT_TRUE(p.predict(kFrameNs + 100'000'000).has_value());
  EXPECT_FALSE(p.predict(kFrameNs + 100'000'001).has_value());
}

TEST(PosePredictor, TimeGoingBackRestartsTheHistory) {
  PosePredictor p;
  p.add(5 * kFrameNs, uniform_motion(5 * kFrameNs));
  p.add(6 * kFrameNs, uniform_motion(6 * kFrameNs));
  p.add(kFrameNs, uniform_motion(kFrameNs));
  EXPECT_EQ(p.poses(), 1u);
}

TEST(So3Log, InvertsExp) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 1000; ++i) {
    Eigen::Vector3d w(u(rng), u(rng), u(rng));
    w *= (3.1 * std::abs(u(rng))) / w.norm();
    EXPECT_LT((so3_log(so3_exp(w)) - w).norm(), 1e-9) << w.transpose();
  }
}

}  // namespace
}  // namespace tetrapulse
