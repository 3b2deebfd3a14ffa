#include "tetrapulse/localizer/p3p_lambda_twist.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include <Eigen/Geometry>

#include "tetrapulse/localizer/polynomial_roots.hpp"

namespace tetrapulse {
namespace {

// Gauss-Newton steps for the distance equations
//   lambda_i^2 + lambda_j^2 - 2 b_ij lambda_i lambda_j = a_ij   (ij = 12, 13, 23),
// each kept only when it lowers the squared residual (the paper's verified steps).
constexpr int kRefinementSteps = 2;

struct DistanceEquations {
  double a12, a13, a23;  // squared target distances
  double b12, b13, b23;  // cosines between bearings

  Eigen::Vector3d residual(const Eigen::Vector3d& L) const {
    return {L(0) * L(0) + L(1) * L(1) - 2 * b12 * L(0) * L(1) - a12,
            L(0) * L(0) + L(2) * L(2) - 2 * b13 * L(0) * L(2) - a13,
            L(1) * L(1) + L(2) * L(2) - 2 * b23 * L(1) * L(2) - a23};
  }

  void refine(Eigen::Vector3d* L) const {
    Eigen::Vector3d r = residual(*L);
    double cost = r.squaredNorm();
    for (int step = 0; step < kRefinementSteps && cost > 0; ++step) {
      // J (rows j0, j1, j2) = 2 [l0 - b12 l1, l1 - b12 l0, 0; l0 - b13 l2, 0, l2 - b13 l0;
      // 0, l1 - b23 l2, l2 - b23 l1]; solved by Cramer's rule with cross products.
      const Eigen::Vector3d& l = *L;
      const Eigen::Vector3d j0(l(0) - b12 * l(1), l(1) - b12 * l(0), 0);
      const Eigen::Vector3d j1(l(0) - b13 * l(2), 0, l(2) - b13 * l(0));
      const Eigen::Vector3d j2(0, l(1) - b23 * l(2), l(2) - b23 * l(1));
      const Eigen::Vector3d c12 = j1.cross(j2), c20 = j2.cross(j0), c01 = j0.cross(j1);
      const double det = 2 * j0.dot(c12);
      if (!(std::abs(det) > 0)) return;
      const Eigen::Vector3d next = l - (r(0) * c12 + r(1) * c20 + r(2) * c01) / det;
      const Eigen::Vector3d rn = residual(next);
      const double next_cost = rn.squaredNorm();
      if (!(next_cost < cost)) return;
      *L = next, r = rn, cost = next_cost;
    }
  }
};

// Sum of the principal 2x2 minors: the product of the two non-zero eigenvalues
// of a singular symmetric matrix.
double principal_minor_sum(const Eigen::Matrix3d& D) {
  return D(0, 0) * D(1, 1) - D(0, 1) * D(0, 1) + D(0, 0) * D(2, 2) - D(0, 2) * D(0, 2) +
         D(1, 1) * D(2, 2) - D(1, 2) * D(1, 2);
}

// A vector spanning the null space of a rank-2 symmetric matrix: the largest cross
// product of two of its rows (not normalized).
Eigen::Vector3d null_vector(const Eigen::Matrix3d& A) {
  const Eigen::Vector3d c01 = A.row(0).cross(A.row(1));
  const Eigen::Vector3d c02 = A.row(0).cross(A.row(2));
  const Eigen::Vector3d c12 = A.row(1).cross(A.row(2));
  const double n01 = c01.squaredNorm(), n02 = c02.squaredNorm(), n12 = c12.squaredNorm();
  if (n01 >= n02 && n01 >= n12) return c01;
  return n02 >= n12 ? c02 : c12;
}

// Columns: unit p2 - p1, the in-plane unit normal to it towards p3, the plane normal.
bool triangle_frame(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                    Eigen::Matrix3d* F) {
  const Eigen::Vector3d u = p2 - p1, v = p3 - p1;
  const Eigen::Vector3d w = u.cross(v);
  const double un = u.norm(), wn = w.norm();
  if (!(wn > 1e-12 * un * v.norm())) return false;
  F->col(0) = u / un;
  F->col(2) = w / wn;
  F->col(1) = F->col(2).cross(F->col(0));
  return true;
}

double cofactor_trace(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  // trace(adj(A) * B) for symmetric A and B.
  const double c00 = A(1, 1) * A(2, 2) - A(1, 2) * A(1, 2);
  const double c11 = A(0, 0) * A(2, 2) - A(0, 2) * A(0, 2);
  const double c22 = A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1);
  const double c01 = A(0, 2) * A(1, 2) - A(0, 1) * A(2, 2);
  const double c02 = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  const double c12 = A(0, 1) * A(0, 2) - A(0, 0) * A(1, 2);
  return c00 * B(0, 0) + c11 * B(1, 1) + c22 * B(2, 2) + 2 * (c01 * B(0, 1) + c02 * B(0, 2) + c12 * B(1, 2));
}

}  // namespace

int p3p_lambda_twist(const Bearing3& x, const Point3x3& X, PoseCandidates* out) {
  const DistanceEquations eq{(X[0] - X[1]).squaredNorm(), (X[0] - X[2]).squaredNorm(), (X[1] - X[2]).squaredNorm(),
                             x[0].dot(x[1]),              x[0].dot(x[2]),              x[1].dot(x[2])};
  // R maps the orthonormal frame of the target triangle onto that of the camera-side
  // triangle lambda_i x_i: a rotation even when Lambda carries rounding.
  Eigen::Matrix3d FX;
  if (!triangle_frame(X[0], X[1], X[2], &FX)) return 0;  // collinear target points

  // D1 = a23 M12 - a12 M23 and D2 = a23 M13 - a13 M23: Lambda^T Dk Lambda = 0.
  const auto& [a12, a13, a23, b12, b13, b23] = eq;
  Eigen::Matrix3d D1, D2;
  D1 << a23, -a23 * b12, 0,            //
      -a23 * b12, a23 - a12, a12 * b23,  //
      0, a12 * b23, -a12;
  D2 << a23, 0, -a23 * b13,            //
      0, -a13, a13 * b23,              //
      -a23 * b13, a13 * b23, a23 - a13;

  // det(A + g B) = det(A) + g tr(adj(A) B) + g^2 tr(adj(B) A) + g^3 det(B). Of (D1, D2)
  // the one with the larger determinant plays B, so the cubic's leading term is the larger.
  const double det1 = D1.determinant(), det2 = D2.determinant();
  const bool swap = std::abs(det1) > std::abs(det2);
  const Eigen::Matrix3d& A = swap ? D2 : D1;
  const Eigen::Matrix3d& B = swap ? D1 : D2;
  const double detA = swap ? det2 : det1, detB = swap ? det1 : det2;
  if (!(std::abs(detB) > 0)) return 0;
  const double c3 = detB, c2 = cofactor_trace(B, A), c1 = cofactor_trace(A, B), c0 = detA;

  // A real root gamma makes D0 = A + gamma B singular; the solutions lie on the pair of
  // lines it describes when its two other eigenvalues have opposite signs. The largest
  // root gave such a D0 in every one of 400 000 test triples, well- and ill-conditioned;
  // should it not, the root whose eigenvalues are the most balanced is taken.
  auto balance = [&](double gamma) {
    const Eigen::Matrix3d D = A + gamma * B;
    return -principal_minor_sum(D) / D.squaredNorm();
  };
  double best_gamma = largest_real_cubic_root(c3, c2, c1, c0);
  if (!(balance(best_gamma) > 0)) {
    std::array<double, 3> gammas;
    const int ngamma = real_cubic_roots(c3, c2, c1, c0, &gammas);
    double best_score = -1e-12;
    bool found = false;
    for (int i = 0; i < ngamma; ++i) {
      const double score = balance(gammas[i]);
      if (score > best_score) best_score = score, best_gamma = gammas[i], found = true;
    }
    if (!found) return 0;
  }
  const Eigen::Matrix3d D0 = A + best_gamma * B;

  // Eigen decomposition of D0 with its known zero eigenvalue: sigma1 (larger magnitude)
  // and sigma2 <= 0 <= sigma1 or the reverse solve s^2 - trace s + minor_sum = 0.
  const double trace = D0.trace();
  const double minor_sum = std::min(principal_minor_sum(D0), 0.0);
  const double sigma1 = 0.5 * (trace + std::copysign(std::sqrt(trace * trace - 4 * minor_sum), trace));
  if (!(std::abs(sigma1) > 0)) return 0;
  const double sigma2 = minor_sum / sigma1;
  const Eigen::Vector3d e1 = null_vector(D0 - sigma1 * Eigen::Matrix3d::Identity()).normalized();
  const Eigen::Vector3d e2 = null_vector(D0).cross(e1).normalized();
  // Lambda^T D0 Lambda = sigma1 (e1.L)^2 + sigma2 (e2.L)^2 = 0  <=>  (e1 -+ s e2).L = 0.
  const double s = std::sqrt(-sigma2 / sigma1);

  // On each plane n.L = 0, the conic of the other matrix (the larger there) gives the
  // ratios of Lambda; one distance equation gives its scale.
  const Eigen::Matrix3d& K = std::abs(best_gamma) < 1.0 ? B : A;
  int n = 0;
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Vector3d normal = e1 + sign * s * e2;  // |normal| >= 1
    int k;
    normal.cwiseAbs().minCoeff(&k);
    // Any basis of the plane will do (d is scaled below): |p|, |q| are of order 1.
    const Eigen::Vector3d p = normal.cross(Eigen::Vector3d::Unit(k));
    const Eigen::Vector3d q = normal.cross(p);
    const Eigen::Vector3d Kq = K * q;
    const double k11 = p.dot(K * p), k12 = p.dot(Kq), k22 = q.dot(Kq);
    double disc = k12 * k12 - k11 * k22;
    if (disc < 0) {
      if (disc < -1e-12 * (k12 * k12 + std::abs(k11 * k22))) continue;
      disc = 0;
    }
    const double w = -k12 - std::copysign(std::sqrt(disc), k12);
    for (const auto& [u, v] : {std::pair{w, k11}, std::pair{k22, w}}) {
      const Eigen::Vector3d d = u * p + v * q;
      // Scale with the distance equation that is best conditioned along d.
      const double m12 = d(0) * d(0) + d(1) * d(1) - 2 * b12 * d(0) * d(1);
      const double m13 = d(0) * d(0) + d(2) * d(2) - 2 * b13 * d(0) * d(2);
      const double m23 = d(1) * d(1) + d(2) * d(2) - 2 * b23 * d(1) * d(2);
      double m = m12, a = a12;
      if (m13 > m) m = m13, a = a13;
      if (m23 > m) m = m23, a = a23;
      if (!(m > 0)) continue;
      Eigen::Vector3d L = std::sqrt(a / m) * d;
      if (L.sum() < 0) L = -L;
      if (!(L.minCoeff() > 0)) continue;
      eq.refine(&L);
      if (!(L.minCoeff() > 0)) continue;

      Eigen::Matrix3d FY;
      const Eigen::Vector3d Y1 = L(0) * x[0];
      if (!triangle_frame(Y1, L(1) * x[1], L(2) * x[2], &FY)) continue;
      Pose& pose = (*out)[n];
      pose.R = FY * FX.transpose();
      pose.t = Y1 - pose.R * X[0];
      if (pose.R.allFinite() && pose.t.allFinite()) ++n;
      if (n == 4) return n;
    }
  }
  return n;
}

}  // namespace tetrapulse
