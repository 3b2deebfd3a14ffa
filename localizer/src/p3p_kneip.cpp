#include "tetrapulse/localizer/p3p_kneip.hpp"

#include <algorithm>
#include <cmath>

#include "tetrapulse/localizer/polynomial_roots.hpp"
#include "vec3.hpp"

// Speed (BENCHMARKS.md): scalar vectors (vec3.hpp), index arithmetic for the
// data-dependent choices, a division shared where the paper divides twice.
namespace tetrapulse {
namespace {

// Squaring in the quartic's derivation admits roots that do not see X_3 along x_3.
// On well-conditioned triples they miss it by 0.09 rad or more while genuine roots
// hit it to 1e-7 rad; only near the danger cylinder do the two kinds merge.
constexpr double kMaxBearingError = 1e-4;

}  // namespace

int p3p_kneip(const Bearing3& x, const Point3x3& X, PoseCandidates* out) {
  const V3 x0 = v3(x[0]), x1 = v3(x[1]), f3 = v3(x[2]);
  const V3 X0 = v3(X[0]), X1 = v3(X[1]), P3 = v3(X[2]);

  // The camera-side frame tau of the paper: t_x = f1, t_z along f1 x f2. theta is taken
  // in [0, pi]; that holds when f3 lies on the negative z side of tau, so f1 and f2
  // (and P1, P2) trade places when it does not, which turns t_z over.
  const V3 z12 = cross(x0, x1);
  const double zz = dot(z12, z12);
  if (!(zz > 1e-24)) return 0;  // f1 and f2 parallel
  // (Indexed by the comparison, which is data: no branch.)
  const int swap = int(dot(f3, z12) > 0);
  const V3 bearings[2] = {x0, x1}, points[2] = {X0, X1};
  const V3 f1 = bearings[swap], P1 = points[swap], P2 = points[1 - swap];
  const double inv_sin_beta = 1 / std::sqrt(zz);  // |f1 x f2| = sin(beta)
  const V3 tz = ((1 - 2 * swap) * inv_sin_beta) * z12, tx = f1, ty = cross(tz, tx);
  const V3 f3_tau{dot(tx, f3), dot(ty, f3), dot(tz, f3)};
  if (!(std::abs(f3_tau.z) > 1e-12)) return 0;  // the three bearings are coplanar

  // The world-side frame eta: origin P1, n_x towards P2, P3 in the x-y plane.
  const V3 u = P2 - P1, v = P3 - P1;
  const V3 w = cross(u, v);
  const double uu = dot(u, u), ww = dot(w, w);
  if (!(uu > 0)) return 0;
  if (!(ww > 1e-24 * uu * uu)) return 0;  // collinear target points
  const double d12 = std::sqrt(uu), inv_d12 = 1 / d12;
  const V3 nx = inv_d12 * u, nz = (1 / std::sqrt(ww)) * w, ny = cross(nz, nx);
  const double p1 = dot(nx, v), p2 = dot(ny, v);

  const double inv_f3z = 1 / f3_tau.z;
  const double phi1 = f3_tau.x * inv_f3z, phi2 = f3_tau.y * inv_f3z;
  const double b = dot(x0, x1) * inv_sin_beta;  // cot(beta), beta the angle between f1 and f2

  // The quartic a4 cos^4 + a3 cos^3 + a2 cos^2 + a1 cos + a0 = 0 in cos(theta) (paper, Eq. 11).
  const double phi1_2 = phi1 * phi1, phi2_2 = phi2 * phi2;
  const double p1_2 = p1 * p1, p1_3 = p1_2 * p1, p1_4 = p1_2 * p1_2;
  const double p2_2 = p2 * p2, p2_3 = p2_2 * p2, p2_4 = p2_2 * p2_2;
  const double d12_2 = uu, b_2 = b * b;
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
  int n = 0;
  for (int i = 0; i < nroots; ++i) {
    const double cos_theta = std::clamp(roots[i], -1.0, 1.0);
    const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
    // cot(alpha) = num / den, alpha the angle at P1 between P1->P2 and P1->C (paper,
    // Eq. 12), with numerator and denominator times phi2 (phi1 / phi2 = f3_tau.x /
    // f3_tau.y). alpha is in (0, pi): sin = |den| / h, cos = sign(den) num / h with
    // h = |(num, den)|, one division fewer than through cot itself.
    const double num = f3_tau.x * p1 + f3_tau.y * (cos_theta * p2 - d12 * b);
    const double den = f3_tau.x * cos_theta * p2 + f3_tau.y * (d12 - p1);
    const double inv_h = 1.0 / std::sqrt(num * num + den * den);
    const double sin_alpha = std::abs(den) * inv_h;
    const double cos_alpha = std::copysign(inv_h, den) * num;

    // Camera centre C = P1 + N^T C_eta and R = T^T Q N (paper, Eqs. 5 and 6), with
    // Q N's rows -cos_a n_x - sin_a g, sin_a n_x - cos_a g, h for g = cos_t n_y + sin_t n_z
    // and h = cos_t n_z - sin_t n_y; C_eta = -k (first row), k = d12 (sin_a b + cos_a).
    const V3 g = cos_theta * ny + sin_theta * nz, h = cos_theta * nz - sin_theta * ny;
    const V3 m0 = (-cos_alpha) * nx - sin_alpha * g, m1 = sin_alpha * nx - cos_alpha * g;
    const double k = d12 * (sin_alpha * b + cos_alpha);
    const V3 C = P1 - k * m0;
    // Rows of R = T^T (Q N): T's columns are t_x, t_y, t_z as rows of T^T.
    const V3 R0 = tx.x * m0 + ty.x * m1 + tz.x * h;
    const V3 R1 = tx.y * m0 + ty.y * m1 + tz.y * h;
    const V3 R2 = tx.z * m0 + ty.z * m1 + tz.z * h;
    auto in_camera = [&](const V3& p) {  // R (p - C)
      const V3 q = p - C;
      return V3{dot(R0, q), dot(R1, q), dot(R2, q)};
    };
    const V3 t = in_camera({0, 0, 0});  // -R C
    // Drop the spurious roots and the mirror poses that see a point behind the camera
    // (|cos_theta| beyond 1 is not a pose either).
    const V3 Y3 = in_camera(P3);
    const V3 e3 = cross(Y3, f3);
    // Every test evaluated and and-ed as integers: no branch per test.
    const unsigned valid =
        unsigned{std::abs(roots[i]) <= 1.0 + 1e-9} & unsigned{dot(Y3, f3) > 0} &
        unsigned{dot(e3, e3) < kMaxBearingError * kMaxBearingError * dot(Y3, Y3)} &
        unsigned{dot(x0, in_camera(X0)) > 0} & unsigned{dot(x1, in_camera(X1)) > 0} &
        unsigned{std::isfinite(R0.x + R0.y + R0.z + R1.x + R1.y + R1.z + R2.x + R2.y + R2.z + t.x + t.y + t.z)};
    // Written whether valid or not (the next root overwrites it): no branch.
    Pose& pose = (*out)[n];
    pose.R << R0.x, R0.y, R0.z, R1.x, R1.y, R1.z, R2.x, R2.y, R2.z;
    pose.t << t.x, t.y, t.z;
    n += valid;
  }
  return n;
}

}  // namespace tetrapulse
