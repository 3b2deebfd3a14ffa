#include "tetrapulse/localizer/sphere_image.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace tetrapulse {

bool sphere_image_centroid(const CameraModel& camera, const Eigen::Vector3d& centre, double radius,
                           Eigen::Vector2d* px, int rim_points) {
  const double distance = centre.norm();
  if (!(radius >= 0) || !(distance > radius) || rim_points < 3) return false;
  Eigen::Vector2d origin;
  if (!camera.project(centre, &origin)) return false;
  if (radius == 0) {
    *px = origin;
    return true;
  }
  const Eigen::Vector3d c = centre / distance;
  const double sin_a = radius / distance, cos_a = std::sqrt(1 - sin_a * sin_a);
  const Eigen::Vector3d e1 = c.unitOrthogonal(), e2 = c.cross(e1);
  // Green's theorem over the projected rim q(phi), phi in [0, 2 pi):
  //   area = 1/2 \oint (x y' - y x'),  moments = (1/2 \oint x^2 y', -1/2 \oint y^2 x'),
  // with q' from the projection's Jacobian. The integrands are smooth and periodic,
  // so the trapezoid rule converges geometrically in rim_points. Pixels are taken
  // relative to the centre's pixel for precision.
  double area = 0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (int k = 0; k < rim_points; ++k) {
    const double phi = 2 * M_PI * k / rim_points;
    const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    const Eigen::Vector3d ray = cos_a * c + sin_a * (cos_phi * e1 + sin_phi * e2);
    const Eigen::Vector3d dray = sin_a * (cos_phi * e2 - sin_phi * e1);
    Eigen::Vector2d q;
    Eigen::Matrix<double, 2, 3> J;
    if (!camera.project(ray, &q, &J)) return false;
    q -= origin;
    const Eigen::Vector2d dq = J * dray;
    area += q.x() * dq.y() - q.y() * dq.x();
    moment += Eigen::Vector2d(q.x() * q.x() * dq.y(), -q.y() * q.y() * dq.x());
  }
  if (!(std::abs(area) > 0)) return false;
  *px = origin + moment / area;  // the common factors (1/2, 2 pi / rim_points) cancel
  return px->allFinite();
}

}  // namespace tetrapulse
