#pragma once
// Rigid poses. Frames and units follow docs/rig-dataset.md: metres, OpenCV camera
// frame (x right, y down, z forward), and a target pose (R, t) maps target
// coordinates to camera coordinates:  p_C = R * p_T + t.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tetrapulse {

struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return R * p + t; }
  Pose inverse() const { return Pose{R.transpose(), -(R.transpose() * t)}; }
  // (this * other): apply `other` first.
  Pose operator*(const Pose& other) const { return Pose{R * other.R, R * other.t + t}; }

  // Hamilton unit quaternion of R with qw >= 0 (the sign the contract's files use).
  Eigen::Quaterniond quaternion() const {
    Eigen::Quaterniond q(R);
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    return q;
  }
  static Pose from_quaternion(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
    return Pose{q.normalized().toRotationMatrix(), t};
  }
};

// exp([w]x): the rotation by |w| radians about the axis w (Rodrigues' formula).
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& w);

// log(R): the rotation vector w with exp([w]x) = R, |w| in [0, pi].
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);

// Angle of the rotation R_a^T R_b in radians, in [0, pi].
double rotation_angle_between(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb);

}  // namespace tetrapulse
