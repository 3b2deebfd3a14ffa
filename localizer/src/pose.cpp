#include "tetrapulse/localizer/pose.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& w) {
  const double theta2 = w.squaredNorm();
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  // sin(theta)/theta and (1 - cos(theta))/theta^2, by their series near zero.
  double a, b;
  if (theta2 < 1e-8) {
    a = 1 - theta2 / 6;
    b = 0.5 - theta2 / 24;
  } else {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1 - std::cos(theta)) / theta2;
  }
  return Eigen::Matrix3d::Identity() + a * W + b * W * W;
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
  // Eigen's angle-axis conversion goes through the quaternion: stable near 0 and pi.
  const Eigen::AngleAxisd aa(Eigen::Quaterniond(R).normalized());
  return aa.angle() * aa.axis();
}

double rotation_angle_between(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb) {
  // atan2 of (|axis|*sin, cos) stays accurate for small angles, unlike acos((tr-1)/2).
  const Eigen::Matrix3d D = Ra.transpose() * Rb;
  const Eigen::Vector3d s(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  const double c = std::clamp((D.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::atan2(s.norm() / 2.0, c);
}

}  // namespace tetrapulse
