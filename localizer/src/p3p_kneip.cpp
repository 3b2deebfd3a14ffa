#include "tetrapulse/localizer/p3p_kneip.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "tetrapulse/localizer/polynomial_roots.hpp"

namespace tetrapulse {
namespace {

// Squaring in the quartic's derivation admits roots that do not see X_3 along x_3.
// On well-conditioned triples they miss it by 0.09 rad or more while genuine roots
// hit it to 1e-7 rad; only near the danger cylinder do the two kinds merge.
constexpr double kMaxBearingError = 1e-4;

// The camera-side frame tau of the paper: t_x = f1, t_z along f1 x f2.
// Returns false when f1 and f2 are parallel.
bool camera_frame(const Eigen::Vector3d& f1, const Eigen::Vector3d& f2, Eigen::Matrix3d* T) {
  const Eigen::Vector3d z = f1.cross(f2);
  const double n = z.norm();
  if (!(n > 1e-12)) return false;
  T->row(0) = f1;
  T->row(2) = z / n;
  T->row(1) = T->row(2).cross(T->row(0));
  return true;
}

}  // namespace

int p3p_kneip(const Bearing3& x, const Point3x3& X, PoseCandidates* out) {
  Eigen::Vector3d f1 = x[0], f2 = x[1];
  const Eigen::Vector3d& f3 = x[2];
  Eigen::Vector3d P1 = X[0], P2 = X[1];
  const Eigen::Vector3d& P3 = X[2];

  Eigen::Matrix3d T;
  if (!camera_frame(f1, f2, &T)) return 0;
  Eigen::Vector3d f3_tau = T * f3;
  // theta is taken in [0, pi]; that holds when f3 lies on the negative z side of tau.
  if (f3_tau.z() > 0) {
    std::swap(f1, f2);
    std::swap(P1, P2);
    camera_frame(f1, f2, &T);
    f3_tau = T * f3;
  }
  if (!(std::abs(f3_tau.z()) > 1e-12)) return 0;  // the three bearings are coplanar

  // The world-side frame eta: origin P1, n_x towards P2, P3 in the x-y plane.
  const Eigen::Vector3d n_x_raw = P2 - P1;
  const double d12 = n_x_raw.norm();
  if (!(d12 > 0)) return 0;
  const Eigen::Vector3d n_x = n_x_raw / d12;
  Eigen::Vector3d n_z = n_x.cross(P3 - P1);
  const double nz_norm = n_z.norm();
  if (!(nz_norm > 1e-12 * d12)) return 0;  // collinear target points
  n_z /= nz_norm;
  Eigen::Matrix3d N;
  N.row(0) = n_x;
  N.row(1) = n_z.cross(n_x);
  N.row(2) = n_z;
  const Eigen::Vector3d P3_eta = N * (P3 - P1);

  const double phi1 = f3_tau.x() / f3_tau.z();
  const double phi2 = f3_tau.y() / f3_tau.z();
  const double p1 = P3_eta.x(), p2 = P3_eta.y();
  // b = cot(beta), beta the angle between f1 and f2.
  const double cos_beta = f1.dot(f2);
  const double b = cos_beta / std::sqrt(1.0 - cos_beta * cos_beta);

  // The quartic a4 cos^4 + a3 cos^3 + a2 cos^2 + a1 cos + a0 = 0 in cos(theta) (paper, Eq. 11).
  const double phi1_2 = phi1 * phi1, phi2_2 = phi2 * phi2;
  const double p1_2 = p1 * p1, p1_3 = p1_2 * p1, p1_4 = p1_2 * p1_2;
  const double p2_2 = p2 * p2, p2_3 = p2_2 * p2, p2_4 = p2_2 * p2_2;
  const double d12_2 = d12 * d12, b_2 = b * b;
  const double a4 = -phi2_2 * p2_4 - phi1_2 * p2_4 - p2_4;
  const double a3 = 2 * p2_3 * d12 * b + 2 * phi2_2 * p2_3 * d12 * b - 2 * phi1 * phi2 * p2_3 * d12;
  const double a2 = -phi2_2 * p1_2 * p2_2 - phi2_2 * p2_2 * d12_2 * b_2 - phi2_2 * p2_2 * d12_2 +
                    phi2_2 * p2_4 + phi1_2 * p2_4 + 2 * p1 * p2_2 * d12 +
                    2 * phi1 * phi2 * p1 * p2_2 * d12 * b - phi1_2 * p1_2 * p2_2 +
                    2 * phi2_2 * p1 * p2_2 * d12 - p2_2 * d12_2 * b_2 - 2 * p1_2 * p2_2;
  const double a1 = 2 * p1_2 * p2 * d12 * b + 2 * phi1 * phi2 * p2_3 * d12 - 2 * phi2_2 * p2_3 * d12 * b -
                    2 * p1 * p2 * d12_2 * b;
  const double a0 = -2 * phi1 * phi2 * p1 * p2_2 * d12 * b + phi2_2 * p2_2 * d12_2 + 2 * p1_3 * d12 -
                    p1_2 * d12_2 + phi2_2 * p1_2 * p2_2 - p1_4 - 2 * phi2_2 * p1 * p2_2 * d12 +
                    phi1_2 * p1_2 * p2_2 + phi2_2 * p2_2 * d12_2 * b_2;

  std::array<double, 4> roots;
  const int nroots = real_quartic_roots(a4, a3, a2, a1, a0, &roots);
  const double phi_ratio = phi1 / phi2;
  int n = 0;
  for (int i = 0; i < nroots; ++i) {
    const double cos_theta = roots[i];
    if (!(std::abs(cos_theta) <= 1.0 + 1e-9)) continue;
    const double cos_theta_c = std::clamp(cos_theta, -1.0, 1.0);
    const double sin_theta = std::sqrt(1.0 - cos_theta_c * cos_theta_c);
    // cot(alpha), alpha the angle at P1 between P1->P2 and P1->C (paper, Eq. 12).
    const double cot_alpha = (phi_ratio * p1 + cos_theta_c * p2 - d12 * b) /
                             (phi_ratio * cos_theta_c * p2 - p1 + d12);
    if (!std::isfinite(cot_alpha)) continue;
    const double sin_alpha = std::sqrt(1.0 / (cot_alpha * cot_alpha + 1.0));
    const double cos_alpha = std::copysign(std::sqrt(1.0 - sin_alpha * sin_alpha), cot_alpha);

    // Camera centre in eta and the rotation from eta to tau (paper, Eqs. 5 and 6).
    const double k = d12 * (sin_alpha * b + cos_alpha);
    const Eigen::Vector3d C_eta(cos_alpha * k, sin_alpha * cos_theta_c * k, sin_alpha * sin_theta * k);
    Eigen::Matrix3d Q;
    Q << -cos_alpha, -sin_alpha * cos_theta_c, -sin_alpha * sin_theta,  //
        sin_alpha, -cos_alpha * cos_theta_c, -cos_alpha * sin_theta,    //
        0.0, -sin_theta, cos_theta_c;
    // Camera orientation in the target frame is N^T Q^T T; our R maps target to camera.
    Pose& pose = (*out)[n];
    pose.R = T.transpose() * Q * N;
    const Eigen::Vector3d C = P1 + N.transpose() * C_eta;
    pose.t = -pose.R * C;
    if (!pose.R.allFinite() || !pose.t.allFinite()) continue;
    // Drop the spurious roots and the mirror poses that see a point behind the camera.
    const Eigen::Vector3d Y3 = pose.apply(X[2]);
    bool valid = Y3.dot(x[2]) > 0 && Y3.cross(x[2]).norm() < kMaxBearingError * Y3.norm();
    for (int j = 0; j < 2; ++j) valid = valid && x[j].dot(pose.apply(X[j])) > 0;
    if (valid) ++n;
  }
  return n;
}

}  // namespace tetrapulse
