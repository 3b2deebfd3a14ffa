#include "tetrapulse/hardware/view_directions.hpp"

#include <cmath>

namespace tetrapulse::hardware {

std::vector<Eigen::Vector3d> fibonacci_directions(int count, bool upper_half) {
  std::vector<Eigen::Vector3d> out;
  if (count <= 0) return out;
  out.reserve(static_cast<size_t>(count));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  const double z_low = upper_half ? 0.0 : -1.0;
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (1.0 - z_low) * (i + 0.5) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.emplace_back(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
  }
  return out;
}

Eigen::Vector3d direction_from_angles(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace tetrapulse::hardware
