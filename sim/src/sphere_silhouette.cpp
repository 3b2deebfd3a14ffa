#include "tetrapulse/sim/sphere_silhouette.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace tetrapulse::sim {

double sphere_half_angle(const Eigen::Vector3d& centre_C, double radius_m) {
  const double d = centre_C.norm();
  if (!(d > radius_m) || !(radius_m > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::asin(radius_m / d);
}

namespace {

// Outline with n points; false when a point does not project. One OpenCV call
// for all of them: a call per point costs more than the projection.
bool outline_points(const LensProjector& camera, const Eigen::Vector3d& c, const Eigen::Vector3d& e1,
                    const Eigen::Vector3d& e2, double alpha, int n, std::vector<Eigen::Vector2d>* out) {
  thread_local std::vector<Eigen::Vector3d> directions;
  directions.resize(static_cast<size_t>(n));
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  // (cos phi, sin phi) by rotation steps: n sin/cos pairs cost more than the projection.
  const double cd = std::cos(2 * M_PI / n), sd = std::sin(2 * M_PI / n);
  double cp = 1, sp = 0;
  for (int k = 0; k < n; ++k) {
    directions[static_cast<size_t>(k)] = ca * c + sa * (cp * e1 + sp * e2);
    const double next_c = cp * cd - sp * sd;
    sp = sp * cd + cp * sd;
    cp = next_c;
  }
  return camera.project(directions, out);
}

}  // namespace

bool sphere_outline(const LensProjector& camera, const Eigen::Vector3d& centre_C, double radius_m, double tolerance_px,
                    std::vector<Eigen::Vector2d>* outline) {
  const double alpha = sphere_half_angle(centre_C, radius_m);
  if (!std::isfinite(alpha)) return false;
  const Eigen::Vector3d c = centre_C.normalized();
  const Eigen::Vector3d helper = std::abs(c.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (helper - c * c.dot(helper)).normalized();
  const Eigen::Vector3d e2 = c.cross(e1);
  // A coarse outline sizes the fine one: a chord of a circle of radius R spanning
  // angle 2 pi / n strays R (1 - cos(pi / n)) ~ R pi^2 / (2 n^2) from it.
  constexpr int kCoarse = 8;
  if (!outline_points(camera, c, e1, e2, alpha, kCoarse, outline)) return false;
  double perimeter = 0;
  for (int k = 0; k < kCoarse; ++k) perimeter += ((*outline)[(k + 1) % kCoarse] - (*outline)[k]).norm();
  const double radius_px = perimeter / (2 * M_PI);
  const double tol = std::max(tolerance_px, 1e-9);
  const int n = static_cast<int>(std::clamp(std::ceil(M_PI * std::sqrt(radius_px / (2 * tol))), 16.0, 8192.0));
  // The inscribed polygon would lose area; put its vertices on a slightly wider cone
  // so that its area is the silhouette's: in gnomonic coordinates the cone is a disc
  // of radius tan(alpha), and an n-gon of circumradius rho has area (n/2) rho^2 sin(2 pi/n).
  const double step = 2 * M_PI / n;
  const double widened = std::atan(std::tan(alpha) * std::sqrt(step / std::sin(step)));
  return outline_points(camera, c, e1, e2, widened, n, outline);
}

}  // namespace tetrapulse::sim
