#include "tetrapulse/sim/silhouette_centroid.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "tetrapulse/sim/sphere_silhouette.hpp"

namespace tetrapulse::sim {

bool pinhole_silhouette_ellipse(const CameraInfo& camera, const Eigen::Vector3d& centre_C, double radius_m,
                                Eigen::Vector2d* centre_px, double* area_px2) {
  const double alpha = sphere_half_angle(centre_C, radius_m);
  if (!std::isfinite(alpha)) return false;
  const Eigen::Vector3d c = centre_C.normalized();
  const double s2 = std::sin(alpha) * std::sin(alpha);
  const double denom = c.z() * c.z() - s2;
  if (!(c.z() > 0) || !(denom > 0)) return false;
  const Eigen::Vector2d m = c.z() * c.head<2>() / denom;
  *centre_px = Eigen::Vector2d(camera.fx * m.x() + camera.cx, camera.fy * m.y() + camera.cy);
  const double a = std::sin(alpha) * std::cos(alpha) / denom;
  const double b = std::sin(alpha) / std::sqrt(denom);
  *area_px2 = M_PI * a * b * camera.fx * camera.fy;
  return true;
}

namespace {

// h(s): pixel of direction c + s1 e1 + s2 e2.
struct Gnomonic {
  const LensProjector& camera;
  Eigen::Vector3d c, e1, e2;
  bool h(double s1, double s2, Eigen::Vector2d* px) const { return camera.project(c + s1 * e1 + s2 * e2, px); }
  // dh/ds by central differences with step d.
  bool jacobian(double s1, double s2, double d, Eigen::Matrix2d* J) const {
    Eigen::Vector2d a, b, p, q;
    if (!h(s1 + d, s2, &a) || !h(s1 - d, s2, &b) || !h(s1, s2 + d, &p) || !h(s1, s2 - d, &q)) return false;
    J->col(0) = (a - b) / (2 * d);
    J->col(1) = (p - q) / (2 * d);
    return true;
  }
};

}  // namespace

bool silhouette_centroid_bias(const LensProjector& camera, const Eigen::Vector3d& centre_C, double radius_m,
                              Eigen::Vector2d* bias_px) {
  const double alpha = sphere_half_angle(centre_C, radius_m);
  if (!std::isfinite(alpha)) return false;
  const Eigen::Vector3d c = centre_C.normalized();
  const Eigen::Vector3d helper = std::abs(c.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (helper - c * c.dot(helper)).normalized();
  const Gnomonic g{camera, c, e1, c.cross(e1)};
  constexpr double d = 1e-4;  // step in tangent units (radians near c)
  Eigen::Vector2d h0, hx1, hx0, hy1, hy0;
  if (!g.h(0, 0, &h0) || !g.h(d, 0, &hx1) || !g.h(-d, 0, &hx0) || !g.h(0, d, &hy1) || !g.h(0, -d, &hy0)) return false;
  const Eigen::Vector2d laplacian = (hx1 + hx0 + hy1 + hy0 - 4 * h0) / (d * d);
  Eigen::Matrix2d J, Jx1, Jx0, Jy1, Jy0;
  if (!g.jacobian(0, 0, d, &J) || !g.jacobian(d, 0, d, &Jx1) || !g.jacobian(-d, 0, d, &Jx0) ||
      !g.jacobian(0, d, d, &Jy1) || !g.jacobian(0, -d, d, &Jy0)) {
    return false;
  }
  const double det = J.determinant();
  if (!(std::abs(det) > 0)) return false;
  const Eigen::Vector2d grad_ln_det((Jx1.determinant() - Jx0.determinant()) / (2 * d * det),
                                    (Jy1.determinant() - Jy0.determinant()) / (2 * d * det));
  const double rho = std::tan(alpha);
  *bias_px = rho * rho / 4 * (laplacian / 2 + J * grad_ln_det);
  return true;
}

}  // namespace tetrapulse::sim
