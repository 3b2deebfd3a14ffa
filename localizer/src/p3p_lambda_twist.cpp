#include "tetrapulse/localizer/p3p_lambda_twist.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "tetrapulse/localizer/polynomial_roots.hpp"
#include "vec3.hpp"

// Speed (BENCHMARKS.md): the solver is bound by latency (a chain of square roots and
// divisions) more than by arithmetic. So: vectors are scalars in registers (vec3.hpp);
// nothing is stored at an index computed late (every later load would wait for its
// address), which is why the lines' axes are 0/1 vectors; choices the predictor cannot
// learn are index arithmetic; and choices it can learn stay branches, so that the CPU
// runs ahead, e.g. posing a refined candidate before its step is verified.
namespace tetrapulse {
namespace {

struct DistanceEquations {
  double a12, a13, a23;  // squared target distances
  double b12, b13, b23;  // cosines between bearings

  V3 residual(const V3& L) const {
    return {L.x * L.x + L.y * L.y - 2 * b12 * L.x * L.y - a12, L.x * L.x + L.z * L.z - 2 * b13 * L.x * L.z - a13,
            L.y * L.y + L.z * L.z - 2 * b23 * L.y * L.z - a23};
  }

  // Gauss-Newton (here Newton: three equations, three unknowns) on the distance
  // equations
  //   lambda_i^2 + lambda_j^2 - 2 b_ij lambda_i lambda_j = a_ij   (ij = 12, 13, 23),
  // each step kept only when it lowers the squared residual (the paper's verified
  // steps). A second step follows only a kept step above 1e-9 |Lambda|: the next one
  // would be below rounding. No step at all when the residual is within 1e-15 of the
  // a_ij (a few roundings): the closed form's Lambda for 89 % of the candidates of
  // well-conditioned triples, where a step moved it by rounding alone. (At 1e-14 the
  // near-collinear triples of p3p_test missed the true pose more often.)
  V3 refine(V3 l) const {
    V3 r = residual(l);
    double cost = dot(r, r);
    if (cost <= 1e-30 * (a12 * a12 + a13 * a13 + a23 * a23)) return l;
    for (int step = 0; step < 2; ++step) {
      // J (rows j0, j1, j2) = 2 [l0 - b12 l1, l1 - b12 l0, 0; l0 - b13 l2, 0, l2 - b13 l0;
      // 0, l1 - b23 l2, l2 - b23 l1]; delta = J^-1 r by Cramer's rule with cross
      // products. A singular J gives a non-finite step, which is not kept.
      const V3 j0{l.x - b12 * l.y, l.y - b12 * l.x, 0};
      const V3 j1{l.x - b13 * l.z, 0, l.z - b13 * l.x};
      const V3 j2{0, l.y - b23 * l.z, l.z - b23 * l.y};
      const V3 c12 = cross(j1, j2), c20 = cross(j2, j0), c01 = cross(j0, j1);
      const V3 delta = (0.5 / dot(j0, c12)) * (r.x * c12 + r.y * c20 + r.z * c01);
      const V3 next = l - delta;
      const V3 rn = residual(next);
      const double next_cost = dot(rn, rn);
      const bool keep = next_cost < cost;
      l = select(keep, next, l), r = select(keep, rn, r), cost = keep ? next_cost : cost;
      if (!(keep && dot(delta, delta) > 1e-18 * dot(l, l))) break;
    }
    return l;
  }
};

// A symmetric 3x3 matrix by its entries; s[i][j] for either order of i, j.
struct Sym3 {
  double s[3][3];

  Sym3(double xx, double xy, double xz, double yy, double yz, double zz)
      : s{{xx, xy, xz}, {xy, yy, yz}, {xz, yz, zz}} {}
  Sym3 plus(double g, const Sym3& o) const {
    return {s[0][0] + g * o.s[0][0], s[0][1] + g * o.s[0][1], s[0][2] + g * o.s[0][2],
            s[1][1] + g * o.s[1][1], s[1][2] + g * o.s[1][2], s[2][2] + g * o.s[2][2]};
  }
  // Sum of the principal 2x2 minors: when one eigenvalue is zero, the product of the
  // other two.
  double minor_sum() const {
    return s[1][1] * s[2][2] - s[1][2] * s[1][2] + s[0][0] * s[2][2] - s[0][2] * s[0][2] + s[0][0] * s[1][1] -
           s[0][1] * s[0][1];
  }
  double squared_norm() const {
    double sum = 0;
    for (const auto& row : s)
      for (const double v : row) sum += v * v;
    return sum;
  }
};

// Index of the entry of v (3 entries) with the largest magnitude, by arithmetic on
// the comparisons (no branch to mispredict).
int largest_magnitude(const double* v) {
  const double a0 = std::abs(v[0]), a1 = std::abs(v[1]), a2 = std::abs(v[2]);
  const int k = int(a1 > a0);
  return k + (2 - k) * int(a2 > std::max(a0, a1));
}

// 2^-e for |v| = 2^e (1 + f), 0 <= f < 1, from the exponent bits: scaling by it is
// exact. (0 and subnormals give 2^1023, infinities and NaN a NaN or zero.)
double inverse_power_of_two(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = (2046 - ((bits >> 52) & 0x7ff)) << 52;
  double scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return scale;
}

// Orthonormal frame of a triangle with edges u and v from one corner: unit u, the unit
// normal to u in the plane (towards v), the unit plane normal u x v. False when u and
// v are (nearly) parallel.
struct Frame {
  V3 e1, e2, e3;

  bool set(const V3& u, const V3& v) {
    const V3 w = cross(u, v);
    const double uu = dot(u, u), ww = dot(w, w);
    if (!(ww > 1e-24 * uu * dot(v, v))) return false;
    e1 = (1 / std::sqrt(uu)) * u, e3 = (1 / std::sqrt(ww)) * w;
    e2 = cross(e3, e1);
    return true;
  }
};

}  // namespace

int p3p_lambda_twist(const Bearing3& xe, const Point3x3& Xe, PoseCandidates* out) {
  const V3 x[3] = {v3(xe[0]), v3(xe[1]), v3(xe[2])};
  const V3 X[3] = {v3(Xe[0]), v3(Xe[1]), v3(Xe[2])};
  // R maps the orthonormal frame of the target triangle onto that of the camera-side
  // triangle lambda_i x_i: a rotation even when Lambda carries rounding. (R from the
  // triangles' edges, [y01 y02 y01 x y02] [d01 d02 d01 x d02]^-1, saves the square
  // roots but is far from a rotation when the points are nearly collinear.)
  const V3 d01 = X[1] - X[0], d02 = X[2] - X[0], d12 = X[2] - X[1];
  Frame FX;
  if (!FX.set(d01, d02)) return 0;  // collinear target points
  const double a12 = dot(d01, d01), a13 = dot(d02, d02), a23 = dot(d12, d12);
  const double b12 = dot(x[0], x[1]), b13 = dot(x[0], x[2]), b23 = dot(x[1], x[2]);
  const DistanceEquations eq{a12, a13, a23, b12, b13, b23};

  // D1 = a23 M12 - a12 M23 and D2 = a23 M13 - a13 M23: Lambda^T Dk Lambda = 0.
  const Sym3 D1(a23, -a23 * b12, 0, a23 - a12, a12 * b23, -a12);
  const Sym3 D2(a23, 0, -a23 * b13, -a13, a13 * b23, a23 - a13);
  // det(D1 + g D2) = -a23 (c3 g^3 + c2 g^2 + c1 g + c0), expanded with s_ij = 1 - b_ij^2.
  const double s12 = 1 - b12 * b12, s13 = 1 - b13 * b13, s23 = 1 - b23 * b23;
  const double t123 = 2 * (1 - b12 * b13 * b23);
  const double c3 = a13 * (a23 * s13 - a13 * s23);
  const double c2 = a12 * (a23 * s13 - 2 * a13 * s23) + a13 * (a23 * t123 - a13 * s23) - a23 * a23 * s13;
  const double c1 = a13 * (a23 * s12 - 2 * a12 * s23) + a12 * (a23 * t123 - a12 * s23) - a23 * a23 * s12;
  const double c0 = a12 * (a23 * s12 - a12 * s23);
  // Of (D1, D2) the one with the larger determinant (c0, c3) plays B, so the cubic's
  // leading term is the larger (chosen by index: a coin toss for the predictor).
  const int swap = int(std::abs(c0) > std::abs(c3));
  const Sym3* const conics[2] = {&D1, &D2};
  const Sym3& A = *conics[swap];
  const Sym3& B = *conics[1 - swap];
  const double cs[4] = {c0, c1, c2, c3};
  const double k3 = cs[3 - 3 * swap], k2 = cs[2 - swap], k1 = cs[1 + swap], k0 = cs[3 * swap];
  if (!(std::abs(k3) > 0)) return 0;

  // A real root gamma makes D0 = A + gamma B singular; the solutions lie on the pair of
  // lines it describes when its two other eigenvalues have opposite signs: a negative
  // minor sum. The largest root gave such a D0 in every one of 400 000 test triples,
  // well- and ill-conditioned; should it not, the root whose eigenvalues are the most
  // balanced is taken.
  double gamma = largest_real_cubic_root(k3, k2, k1, k0);
  Sym3 D0 = A.plus(gamma, B);
  if (!(D0.minor_sum() < 0)) {
    std::array<double, 3> gammas;
    const int ngamma = real_cubic_roots(k3, k2, k1, k0, &gammas);
    double best_score = -1e-12;
    bool found = false;
    for (int i = 0; i < ngamma; ++i) {
      const Sym3 D = A.plus(gammas[i], B);
      const double score = -D.minor_sum() / D.squared_norm();
      if (score > best_score) best_score = score, gamma = gammas[i], found = true;
    }
    if (!found) return 0;
    D0 = A.plus(gamma, B);
  }

  // Split D0 = (u v^T + v u^T) / 2 into its lines u.L = 0 and v.L = 0 without an eigen
  // decomposition: adj(D0) = -(u x v)(u x v)^T / 4, so its column a_c with the largest
  // diagonal magnitude is sigma p, p = +-(u x v) / 2, sigma = sqrt(-adj_cc), and
  // sigma (D0 + [p]x) = sigma u v^T (or v u^T) has rank one: its largest row and column
  // are the two lines. (No division: the lines' scale does not matter.)
  const auto& d = D0.s;
  const double adj01 = d[0][2] * d[1][2] - d[0][1] * d[2][2], adj02 = d[0][1] * d[1][2] - d[0][2] * d[1][1],
               adj12 = d[0][1] * d[0][2] - d[0][0] * d[1][2];
  const double adj[3][3] = {{d[1][1] * d[2][2] - d[1][2] * d[1][2], adj01, adj02},
                            {adj01, d[0][0] * d[2][2] - d[0][2] * d[0][2], adj12},
                            {adj02, adj12, d[0][0] * d[1][1] - d[0][1] * d[0][1]}};
  const double diag[3] = {adj[0][0], adj[1][1], adj[2][2]};
  const int c = largest_magnitude(diag);
  // Only for a double line (the fallback's minor sum near zero) is adj_cc >= 0: p = 0.
  const bool pair = adj[c][c] < 0;
  const double sigma = pair ? std::sqrt(-adj[c][c]) : 1.0;
  const double p0 = pair ? adj[0][c] : 0.0, p1 = pair ? adj[1][c] : 0.0, p2 = pair ? adj[2][c] : 0.0;
  const double C[3][3] = {{sigma * d[0][0], sigma * d[0][1] - p2, sigma * d[0][2] + p1},
                          {sigma * d[0][1] + p2, sigma * d[1][1], sigma * d[1][2] - p0},
                          {sigma * d[0][2] - p1, sigma * d[1][2] + p0, sigma * d[2][2]}};
  // C = sigma u v^T: its row norms go with |u_i|, its column norms with |v_j|, so the
  // pivot C_ij of the largest row and column is also the largest entry of each line.
  double row_norms[3], col_norms[3];
  for (int i = 0; i < 3; ++i) {
    row_norms[i] = C[i][0] * C[i][0] + C[i][1] * C[i][1] + C[i][2] * C[i][2];
    col_norms[i] = C[0][i] * C[0][i] + C[1][i] * C[1][i] + C[2][i] * C[2][i];
  }
  const int ci = largest_magnitude(row_norms), cj = largest_magnitude(col_norms);
  const double unit = inverse_power_of_two(C[ci][cj]);  // exact scaling: |pivot| in [1, 2)

  // On each plane l.L = 0 the conic of the other matrix (the larger there: A = -gamma B
  // on the plane) gives the ratios of Lambda: L = u P + v Q with P = l x e_a, Q = l x e_b,
  // a and b the axes other than the pivot's k (|l_k| largest: P and Q span the plane
  // well). The axes enter as 0/1 vectors, so nothing is indexed at run time. The sum of
  // the distance equations gives the scale (all three terms are positive definite). Up
  // to four candidates with positive depths are gathered, then refined and posed.
  const Sym3& K = *conics[swap ^ int(std::abs(gamma) < 1.0)];
  auto times_K = [&K](const V3& v) {
    const auto& k = K.s;
    return V3{k[0][0] * v.x + k[0][1] * v.y + k[0][2] * v.z, k[0][1] * v.x + k[1][1] * v.y + k[1][2] * v.z,
              k[0][2] * v.x + k[1][2] * v.y + k[2][2] * v.z};
  };
  const double a_sum = a12 + a13 + a23;
  V3 candidates[4];
  int ncandidates = 0;
  const V3 lines[2] = {unit * V3{C[ci][0], C[ci][1], C[ci][2]}, unit * V3{C[0][cj], C[1][cj], C[2][cj]}};
  const int pivots[2] = {cj, ci};  // the pivot's index in each line
  for (int n_line = 0; n_line < 2; ++n_line) {
    const V3& l = lines[n_line];
    const int k = pivots[n_line];
    const V3 ea{double(k == 2), double(k == 0), double(k == 1)};  // e_(k+1 mod 3)
    const V3 eb{double(k == 1), double(k == 2), double(k == 0)};  // e_(k+2 mod 3)
    const V3 P = cross(l, ea), Q = cross(l, eb);
    const V3 KP = times_K(P), KQ = times_K(Q);
    const double k11 = dot(P, KP), k12 = dot(P, KQ), k22 = dot(Q, KQ);
    // A slightly negative discriminant is rounding of a tangency.
    const double disc = k12 * k12 - k11 * k22;
    const bool meets = !(disc < -1e-12 * (k12 * k12 + std::abs(k11 * k22)));
    // The roots u / v of k11 u^2 + 2 k12 u v + k22 v^2 = 0 without cancellation: w / k11
    // and k22 / w.
    const double w = -k12 - std::copysign(std::sqrt(std::max(disc, 0.0)), k12);
    const double uv[2][2] = {{w, k11}, {k22, w}};
    for (int root = 0; root < 2; ++root) {
      const double u = uv[root][0], v = uv[root][1];
      const V3 dir = u * P + v * Q;
      const double m = 2 * (dot(dir, dir) - (b12 * dir.x * dir.y + b13 * dir.x * dir.z + b23 * dir.y * dir.z));
      const bool positive = m > 0;
      // The sign that makes the depths' sum positive; all three must then be.
      const double s = std::copysign(std::sqrt(positive ? a_sum / m : 0.0), dir.x + dir.y + dir.z);
      const V3 L = s * dir;
      candidates[ncandidates] = L;
      ncandidates += meets & positive & (L.x > 0) & (L.y > 0) & (L.z > 0);
    }
  }

  int n = 0;
  for (int q = 0; q < ncandidates; ++q) {
    const V3 L = eq.refine(candidates[q]);
    if (!(L.x > 0 && L.y > 0 && L.z > 0)) continue;
    const V3 y0 = L.x * x[0];
    Frame FY;
    if (!FY.set(L.y * x[1] - y0, L.z * x[2] - y0)) continue;
    // R = [FY] [FX]^T by rows, t = y0 - R X_0; checked in registers, then stored.
    const V3 R0 = FY.e1.x * FX.e1 + FY.e2.x * FX.e2 + FY.e3.x * FX.e3;
    const V3 R1 = FY.e1.y * FX.e1 + FY.e2.y * FX.e2 + FY.e3.y * FX.e3;
    const V3 R2 = FY.e1.z * FX.e1 + FY.e2.z * FX.e2 + FY.e3.z * FX.e3;
    const V3 t{y0.x - dot(R0, X[0]), y0.y - dot(R1, X[0]), y0.z - dot(R2, X[0])};
    // Finite entries have a finite sum (|R_ij| <= 1); an overflowing t is dropped too.
    if (!std::isfinite(R0.x + R0.y + R0.z + R1.x + R1.y + R1.z + R2.x + R2.y + R2.z + t.x + t.y + t.z)) continue;
    Pose& pose = (*out)[n++];
    pose.R << R0.x, R0.y, R0.z, R1.x, R1.y, R1.z, R2.x, R2.y, R2.z;
    pose.t << t.x, t.y, t.z;
  }
  return n;
}

}  // namespace tetrapulse
