#include "tetrapulse/localizer/pose.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {

double rotation_angle_between(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb) {
  // atan2 of (|axis|*sin, cos) stays accurate for small angles, unlike acos((tr-1)/2).
  const Eigen::Matrix3d D = Ra.transpose() * Rb;
  const Eigen::Vector3d s(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  const double c = std::clamp((D.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::atan2(s.norm() / 2.0, c);
}

}  // namespace tetrapulse
