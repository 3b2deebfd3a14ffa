#include "tetrapulse/localizer/camera_model.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "tetrapulse/localizer/polynomial_roots.hpp"

namespace tetrapulse {

const char* distortion_model_name(DistortionModel model) {
  return model == DistortionModel::kPlumbBob ? "plumb_bob" : "equidistant";
}

namespace {

// Fisheye: theta_d(theta) and its derivative.
void fisheye_theta_d(const std::array<double, 5>& k, double theta, double* theta_d, double* dtheta_d) {
  const double t2 = theta * theta, t4 = t2 * t2, t6 = t4 * t2, t8 = t4 * t4;
  *theta_d = theta * (1 + k[0] * t2 + k[1] * t4 + k[2] * t6 + k[3] * t8);
  *dtheta_d = 1 + 3 * k[0] * t2 + 5 * k[1] * t4 + 7 * k[2] * t6 + 9 * k[3] * t8;
}

// Smallest positive root of c[0] + c[1] s + ... + c[4] s^4 (c[0] = 1 > 0: the
// first sign change of a radial map's derivative); infinity when there is none.
double first_positive_root(const std::array<double, 5>& c) {
  int degree = 4;
  while (degree > 0 && c[size_t(degree)] == 0) --degree;
  std::array<double, 4> roots{};
  int n = 0;
  if (degree == 4) {
    n = real_quartic_roots(c[4], c[3], c[2], c[1], c[0], &roots);
  } else if (degree == 3) {
    std::array<double, 3> r3{};
    n = real_cubic_roots(c[3], c[2], c[1], c[0], &r3);
    for (int i = 0; i < n; ++i) roots[size_t(i)] = r3[size_t(i)];
  } else if (degree == 2) {
    const double disc = c[1] * c[1] - 4 * c[2] * c[0];
    if (disc >= 0) {
      const double q = -0.5 * (c[1] + std::copysign(std::sqrt(disc), c[1]));
      roots[0] = q / c[2];
      roots[1] = q != 0 ? c[0] / q : roots[0];
      n = 2;
    }
  } else if (degree == 1) {
    roots[0] = -c[0] / c[1];
    n = 1;
  }
  double first = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    if (roots[size_t(i)] > 0) first = std::min(first, roots[size_t(i)]);
  return first;
}

}  // namespace

CameraModel::CameraModel(const CameraInfo& info)
    : info_(info), max_r2_(std::numeric_limits<double>::infinity()), max_theta_(M_PI / 2) {
  const auto& k = info_.distortion;
  if (info_.model == DistortionModel::kPlumbBob) {
    // d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)] = 1 + 3 k1 s + 5 k2 s^2 + 7 k3 s^3, s = r^2.
    max_r2_ = first_positive_root({1.0, 3 * k[0], 5 * k[1], 7 * k[4], 0.0});
  } else {
    // d theta_d / d theta = 1 + 3 k1 u + 5 k2 u^2 + 7 k3 u^3 + 9 k4 u^4, u = theta^2.
    const double u = first_positive_root({1.0, 3 * k[0], 5 * k[1], 7 * k[2], 9 * k[3]});
    max_theta_ = std::min(M_PI / 2, std::sqrt(u));
  }
}

namespace {

// plumb_bob's distortion at (x, y) in scalars, and its Jacobian J = d(x', y')/d(x, y)
// (row major): the projection runs it for every rim point of every sphere image
// of a refinement, where Eigen's 2 x 2 and 2 x 3 temporaries went through memory.
struct PlumbBob {
  double xd, yd;
  double J00, J01, J10, J11;

  PlumbBob(const std::array<double, 5>& d, double x, double y, bool jacobian) {
    const double k1 = d[0], k2 = d[1], p1 = d[2], p2 = d[3], k3 = d[4];
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
    if (!jacobian) return;
    const double dradial_dr2 = k1 + r2 * (2 * k2 + 3 * k3 * r2);
    const double drx = 2 * x * dradial_dr2, dry = 2 * y * dradial_dr2;
    J00 = radial + x * drx + 2 * p1 * y + 6 * p2 * x;
    J01 = x * dry + 2 * p1 * x + 2 * p2 * y;
    J10 = y * drx + 2 * p1 * x + 2 * p2 * y;
    J11 = radial + y * dry + 6 * p1 * y + 2 * p2 * x;
  }
};

}  // namespace

// Distortion in normalized coordinates, for plumb_bob: (x, y) -> (x', y') and its Jacobian.
bool CameraModel::distort(const Eigen::Vector2d& xy, Eigen::Vector2d* out, Eigen::Matrix2d* J) const {
  const PlumbBob d(info_.distortion, xy.x(), xy.y(), J != nullptr);
  (*out) << d.xd, d.yd;
  if (J) (*J) << d.J00, d.J01, d.J10, d.J11;
  return true;
}

bool CameraModel::project(const Eigen::Vector3d& p, Eigen::Vector2d* px, Eigen::Matrix<double, 2, 3>* J) const {
  const double X = p.x(), Y = p.y(), Z = p.z();
  if (!(Z > 0) || !std::isfinite(X) || !std::isfinite(Y)) return false;
  if (info_.model == DistortionModel::kPlumbBob) {
    const double x = X / Z, y = Y / Z;
    if (!(x * x + y * y < max_r2_)) return false;
    const PlumbBob d(info_.distortion, x, y, J != nullptr);
    (*px) << info_.fx * d.xd + info_.cx, info_.fy * d.yd + info_.cy;
    if (J) {
      // J_d d(x, y)/dp, d(x, y)/dp = [1/Z 0 -X/Z^2; 0 1/Z -Y/Z^2], each sum as a
      // 2 x 2 by 2 x 3 product forms it (a zero term adds nothing).
      const double iz = 1 / Z, ax = -X / (Z * Z), ay = -Y / (Z * Z);
      (*J) << info_.fx * (d.J00 * iz), info_.fx * (d.J01 * iz), info_.fx * (d.J00 * ax + d.J01 * ay),
          info_.fy * (d.J10 * iz), info_.fy * (d.J11 * iz), info_.fy * (d.J10 * ax + d.J11 * ay);
    }
    return std::isfinite(px->x()) && std::isfinite(px->y());
  }
  Eigen::Vector2d xd;
  Eigen::Matrix<double, 2, 3> dxd_dp;
  const double rho = std::hypot(X, Y);
  const double theta = std::atan2(rho, Z);
  if (!(theta < max_theta_)) return false;
  double td, dtd;
  fisheye_theta_d(info_.distortion, theta, &td, &dtd);
  if (rho < 1e-12 * Z) {
    // On the axis theta_d/rho -> 1/Z: the model is a pinhole to first order.
    xd << X / Z, Y / Z;
    if (J) dxd_dp << 1 / Z, 0, -X / (Z * Z), 0, 1 / Z, -Y / (Z * Z);
  } else {
    const double ux = X / rho, uy = Y / rho;
    xd << td * ux, td * uy;
    if (J) {
      const double q = rho * rho + Z * Z;
      const Eigen::RowVector3d dtheta(ux * Z / q, uy * Z / q, -rho / q);
      const double r3 = rho * rho * rho;
      dxd_dp.row(0) = dtd * ux * dtheta + td * Eigen::RowVector3d(Y * Y / r3, -X * Y / r3, 0);
      dxd_dp.row(1) = dtd * uy * dtheta + td * Eigen::RowVector3d(-X * Y / r3, X * X / r3, 0);
    }
  }
  (*px) << info_.fx * xd.x() + info_.cx, info_.fy * xd.y() + info_.cy;
  if (J) {
    J->row(0) = info_.fx * dxd_dp.row(0);
    J->row(1) = info_.fy * dxd_dp.row(1);
  }
  return std::isfinite(px->x()) && std::isfinite(px->y());
}

bool CameraModel::project_along(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, Eigen::Vector2d* px,
                                Eigen::Vector2d* dpx) const {
  if (info_.model != DistortionModel::kPlumbBob) {
    Eigen::Matrix<double, 2, 3> J;
    if (!project(p, px, &J)) return false;
    *dpx = J * dp;
    return true;
  }
  const double X = p.x(), Y = p.y(), Z = p.z();
  if (!(Z > 0) || !std::isfinite(X) || !std::isfinite(Y)) return false;
  const double x = X / Z, y = Y / Z, iz = 1 / Z;  // the pixel exactly as project() gives it
  if (!(x * x + y * y < max_r2_)) return false;
  const PlumbBob d(info_.distortion, x, y, true);
  // d(x, y) = (dX - x dZ, dY - y dZ) / Z, then through J_d.
  const double dx = (dp.x() - x * dp.z()) * iz, dy = (dp.y() - y * dp.z()) * iz;
  (*px) << info_.fx * d.xd + info_.cx, info_.fy * d.yd + info_.cy;
  (*dpx) << info_.fx * (d.J00 * dx + d.J01 * dy), info_.fy * (d.J10 * dx + d.J11 * dy);
  return std::isfinite(px->x()) && std::isfinite(px->y());
}

bool CameraModel::unproject(const Eigen::Vector2d& px, Eigen::Vector3d* bearing) const {
  const Eigen::Vector2d xd((px.x() - info_.cx) / info_.fx, (px.y() - info_.cy) / info_.fy);
  if (!xd.allFinite()) return false;
  if (info_.model == DistortionModel::kPlumbBob) {
    // Newton on distort(x) = xd, from the undistorted guess x = xd.
    Eigen::Vector2d x = xd;
    for (int it = 0; it < 30; ++it) {
      Eigen::Vector2d f;
      Eigen::Matrix2d Jd;
      distort(x, &f, &Jd);
      const Eigen::Vector2d r = f - xd;
      if (r.norm() < 1e-15) break;
      const double det = Jd.determinant();
      if (std::abs(det) < 1e-12) return false;
      x -= Jd.inverse() * r;
    }
    Eigen::Vector2d check;
    distort(x, &check, nullptr);
    if (!((check - xd).norm() < 1e-9) || !(x.squaredNorm() < max_r2_)) return false;
    *bearing = Eigen::Vector3d(x.x(), x.y(), 1.0).normalized();
    return true;
  }
  const double rd = xd.norm();
  if (rd < 1e-15) {
    *bearing = Eigen::Vector3d(0, 0, 1);
    return true;
  }
  // Newton on theta_d(theta) = rd; theta_d is monotonic over the lens's field of view.
  double theta = rd;
  for (int it = 0; it < 30; ++it) {
    double td, dtd;
    fisheye_theta_d(info_.distortion, theta, &td, &dtd);
    if (!(dtd > 1e-9)) return false;
    const double step = (td - rd) / dtd;
    theta -= step;
    if (std::abs(step) < 1e-15) break;
  }
  double td, dtd;
  fisheye_theta_d(info_.distortion, theta, &td, &dtd);
  if (!(std::abs(td - rd) < 1e-9) || !(theta >= 0) || !(theta < max_theta_)) return false;
  const double s = std::sin(theta) / rd;
  *bearing = Eigen::Vector3d(s * xd.x(), s * xd.y(), std::cos(theta));
  return true;
}

bool CameraModel::in_image(const Eigen::Vector2d& px, double margin) const {
  return px.x() >= -0.5 + margin && px.y() >= -0.5 + margin && px.x() < info_.width - 0.5 - margin &&
         px.y() < info_.height - 0.5 - margin;
}

}  // namespace tetrapulse
