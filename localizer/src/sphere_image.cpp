#include "tetrapulse/localizer/sphere_image.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace tetrapulse {
namespace {

// cos and sin of the rim points' angles phi_k = 2 pi k / n: the same for every
// sphere, and a refinement asks for a few dozen spheres a frame.
struct RimAngles {
  int n = 0;
  std::vector<double> cos_phi, sin_phi;

  explicit RimAngles(int points) : n(points) {
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * M_PI * k / n;
      cos_phi.push_back(std::cos(phi));
      sin_phi.push_back(std::sin(phi));
    }
  }
};

// The angles for `rim_points`: kept for the count of the first call (every
// caller so far uses the default), made anew for any other.
const RimAngles& rim_angles(int rim_points, RimAngles* other) {
  static const RimAngles first(rim_points);
  if (first.n == rim_points) return first;
  *other = RimAngles(rim_points);
  return *other;
}

}  // namespace

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
  // with q' the projection's derivative along the rim. The integrands are smooth and periodic,
  // so the trapezoid rule converges geometrically in rim_points. Pixels are taken
  // relative to the centre's pixel for precision.
  RimAngles other(0);
  const RimAngles& angles = rim_angles(rim_points, &other);
  double area = 0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (int k = 0; k < rim_points; ++k) {
    const double cos_phi = angles.cos_phi[size_t(k)], sin_phi = angles.sin_phi[size_t(k)];
    const Eigen::Vector3d ray = cos_a * c + sin_a * (cos_phi * e1 + sin_phi * e2);
    const Eigen::Vector3d dray = sin_a * (cos_phi * e2 - sin_phi * e1);
    Eigen::Vector2d q, dq;
    if (!camera.project_along(ray, dray, &q, &dq)) return false;
    q -= origin;
    area += q.x() * dq.y() - q.y() * dq.x();
    moment += Eigen::Vector2d(q.x() * q.x() * dq.y(), -q.y() * q.y() * dq.x());
  }
  if (!(std::abs(area) > 0)) return false;
  *px = origin + moment / area;  // the common factors (1/2, 2 pi / rim_points) cancel
  return px->allFinite();
}

}  // namespace tetrapulse
