#pragma once
// A constant-velocity Kalman filter on a pose: state (p, v, theta, omega), with
// p the translation (m) and v its rate (m/s), theta a small rotation (rad) about
// the filter's reference rotation R_ref (R = exp([theta]x) R_ref, camera frame)
// and omega the angular velocity (rad/s, camera frame). Between measurements
// the accelerations are white noise of spectral density q (continuous white-
// noise acceleration model, Bar-Shalom et al., "Estimation with Applications to
// Tracking and Navigation", 2001, Sec. 6.2.2):
//   x(t + dt) = F x(t),   Q per axis = q [dt^3/3, dt^2/2; dt^2/2, dt].
// A measured pose (R_m, t_m) is the observation z = (t_m, log(R_m R_ref^T));
// after each update theta is folded into R_ref (error-state form).
// Times in integer nanoseconds of rig time.
#include <cstdint>

#include <Eigen/Core>

#include "tetrapulse/localizer/pose.hpp"

namespace tetrapulse {

struct KalmanNoise {
  double acceleration = 4.0;          // q of the translation, (m/s^2)^2 / Hz
  double angular_acceleration = 40;   // q of the rotation, (rad/s^2)^2 / Hz
};

class ConstantVelocityKalman {
 public:
  ConstantVelocityKalman() = default;
  explicit ConstantVelocityKalman(KalmanNoise noise) : noise_(noise) {}

  bool initialised() const { return initialised_; }
  void reset() { initialised_ = false; }

  // Starts from `pose` with zero velocity (velocity standard deviations 1 m/s, 3 rad/s)
  // or, once started, predicts to t_ns and updates with the measured pose.
  void update(int64_t t_ns, const Pose& pose, double position_sigma_m, double rotation_sigma_rad);

  // The state's pose propagated to t_ns (no update).
  Pose predict(int64_t t_ns) const;

  const Eigen::Vector3d& velocity() const { return velocity_; }
  const Eigen::Vector3d& angular_velocity() const { return angular_velocity_; }

 private:
  using Matrix12 = Eigen::Matrix<double, 12, 12>;
  void propagate(double dt_s, Matrix12* F, Matrix12* Q) const;

  KalmanNoise noise_;
  bool initialised_ = false;
  int64_t t_ns_ = 0;
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();  // R_ref
  Eigen::Vector3d angular_velocity_ = Eigen::Vector3d::Zero();
  Matrix12 covariance_ = Matrix12::Identity();  // order p, v, theta, omega
};

}  // namespace tetrapulse
