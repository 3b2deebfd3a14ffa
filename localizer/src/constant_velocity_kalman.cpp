#include "tetrapulse/localizer/constant_velocity_kalman.hpp"

#include <Eigen/Cholesky>

namespace tetrapulse {

void ConstantVelocityKalman::propagate(double dt, Matrix12* F, Matrix12* Q) const {
  F->setIdentity();
  Q->setZero();
  const double q[2] = {noise_.acceleration, noise_.angular_acceleration};
  for (int block = 0; block < 2; ++block) {
    const int x = 6 * block, rate = 6 * block + 3;  // p/v or theta/omega
    F->block<3, 3>(x, rate) = dt * Eigen::Matrix3d::Identity();
    Q->block<3, 3>(x, x) = q[block] * dt * dt * dt / 3 * Eigen::Matrix3d::Identity();
    Q->block<3, 3>(x, rate) = q[block] * dt * dt / 2 * Eigen::Matrix3d::Identity();
    Q->block<3, 3>(rate, x) = Q->block<3, 3>(x, rate);
    Q->block<3, 3>(rate, rate) = q[block] * dt * Eigen::Matrix3d::Identity();
  }
}

void ConstantVelocityKalman::update(int64_t t_ns, const Pose& pose, double position_sigma_m,
                                    double rotation_sigma_rad) {
  if (!initialised_ || t_ns <= t_ns_) {
    initialised_ = true;
    t_ns_ = t_ns;
    position_ = pose.t;
    rotation_ = pose.R;
    velocity_.setZero();
    angular_velocity_.setZero();
    covariance_.setZero();
    covariance_.block<3, 3>(0, 0).diagonal().setConstant(position_sigma_m * position_sigma_m);
    covariance_.block<3, 3>(3, 3).diagonal().setConstant(1.0);
    covariance_.block<3, 3>(6, 6).diagonal().setConstant(rotation_sigma_rad * rotation_sigma_rad);
    covariance_.block<3, 3>(9, 9).diagonal().setConstant(9.0);
    return;
  }
  // Predict to t_ns.
  const double dt = double(t_ns - t_ns_) * 1e-9;
  Matrix12 F, Q;
  propagate(dt, &F, &Q);
  position_ += dt * velocity_;
  rotation_ = so3_exp(dt * angular_velocity_) * rotation_;
  covariance_ = F * covariance_ * F.transpose() + Q;
  t_ns_ = t_ns;

  // Update with z = (t_m - p, log(R_m R_ref^T)); H picks p and theta.
  Eigen::Matrix<double, 6, 1> y;
  y << pose.t - position_, so3_log(pose.R * rotation_.transpose());
  Eigen::Matrix<double, 6, 12> H = Eigen::Matrix<double, 6, 12>::Zero();
  H.block<3, 3>(0, 0).setIdentity();
  H.block<3, 3>(3, 6).setIdentity();
  Eigen::Matrix<double, 6, 6> S = H * covariance_ * H.transpose();
  S.block<3, 3>(0, 0).diagonal().array() += position_sigma_m * position_sigma_m;
  S.block<3, 3>(3, 3).diagonal().array() += rotation_sigma_rad * rotation_sigma_rad;
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(S);
  if (llt.info() != Eigen::Success) return;
  const Eigen::Matrix<double, 12, 6> K = covariance_ * H.transpose() * llt.solve(Eigen::Matrix<double, 6, 6>::Identity());
  const Eigen::Matrix<double, 12, 1> dx = K * y;
  position_ += dx.segment<3>(0);
  velocity_ += dx.segment<3>(3);
  rotation_ = so3_exp(dx.segment<3>(6)) * rotation_;
  angular_velocity_ += dx.segment<3>(9);
  covariance_ = (Matrix12::Identity() - K * H) * covariance_;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
}

Pose ConstantVelocityKalman::predict(int64_t t_ns) const {
  const double dt = double(t_ns - t_ns_) * 1e-9;
  return Pose{so3_exp(dt * angular_velocity_) * rotation_, position_ + dt * velocity_};
}

}  // namespace tetrapulse
