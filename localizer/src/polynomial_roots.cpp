#include "tetrapulse/localizer/polynomial_roots.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "branchless.hpp"

namespace tetrapulse {
namespace {

// Newton steps on a monic polynomial (coefficients c[0..n-1] of x^(n-1)..x^0
// below the leading 1); a step is kept only when it lowers |p(x)|. A kept step
// below 1e-10 |x| ends the polish: the next would be below rounding. No step is
// taken when it would be below 1e-15 |x| (|p| <= 1e-15 |x p'|, compared without the
// division): most of Ferrari's roots of the P3P quartic already are.
template <int N>
double polish(const std::array<double, N>& c, double x) {
  auto eval = [&](double v, double* dv) {
    double p = 1.0, dp = 0.0;
    for (int i = 0; i < N; ++i) {
      dp = dp * v + p;
      p = p * v + c[i];
    }
    *dv = dp;
    return p;
  };
  double d;
  double f = eval(x, &d);
  if (std::abs(f) <= 1e-15 * std::abs(x * d)) return x;
  for (int it = 0; it < 2 && f != 0.0; ++it) {
    if (!(std::abs(d) > 0.0)) break;
    const double step = f / d;
    const double next = x - step;
    double dn;
    const double fn = eval(next, &dn);
    if (!(std::abs(fn) < std::abs(f))) break;
    x = next, f = fn, d = dn;
    if (std::abs(step) <= 1e-10 * std::abs(x)) break;
  }
  return x;
}

// One Newton step on a monic polynomial, kept only when it lowers |p(x)| (a zero
// derivative gives a non-finite step, which is not kept).
template <int N>
double newton_step(const std::array<double, N>& c, double x) {
  double p = 1.0, dp = 0.0;
  for (int i = 0; i < N; ++i) {
    dp = dp * x + p;
    p = p * x + c[i];
  }
  const double next = x - p / dp;
  double pn = 1.0;
  for (int i = 0; i < N; ++i) pn = pn * next + c[i];
  return std::abs(pn) < std::abs(p) ? next : x;
}

// |v|^(-1/3) for v != 0: a first guess from the bits of v (the exponent divided by
// three: a 3.4 % error at most), refined by two division-free fourth-order steps
// r <- r (1 - e)^(-1/3) ~ r (1 + e/3 + 2e^2/9 + 14e^3/81), e = 1 - |v| r^3.
double inverse_cube_root(double v) {
  const double a = std::abs(v);
  if (!(a >= DBL_MIN && a <= DBL_MAX)) return 1.0 / std::cbrt(a);  // subnormal, inf, NaN
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  // 0x5540... = (1023 + 1023 / 3) << 52 makes the exponent -(e / 3); lowered to
  // 0x553ef0fc... it minimises the guess's largest relative error.
  bits = 0x553ef0fcb4077759ull - bits / 3;
  double r;
  std::memcpy(&r, &bits, sizeof r);
  for (int i = 0; i < 2; ++i) {
    const double e = 1.0 - a * (r * r * r);
    r += r * e * (1.0 / 3.0 + e * (2.0 / 9.0 + e * (14.0 / 81.0)));
  }
  return r;
}

// Real roots of y^2 + B y + C = 0. A slightly negative discriminant (rounding of
// a double root) counts as zero. Writes both values either way (the callers select).
int real_quadratic_roots(double B, double C, double* y) {
  const double disc = B * B - 4.0 * C;
  const bool real = !(disc < -1e-12 * (B * B + 4.0 * std::abs(C)));
  // The root without cancellation first; the other from the product of the roots.
  const double big = -0.5 * (B + std::copysign(std::sqrt(std::max(disc, 0.0)), B));
  y[0] = big;
  y[1] = big != 0.0 ? C / big : 0.0;
  return real ? 2 : 0;
}

// x^3 + a x^2 + b x + c = 0 with x = t - a/3 becomes t^3 + p t + q = 0.
struct DepressedCubic {
  double shift, third_p, half_q, disc;

  DepressedCubic(double a, double b, double c) {
    constexpr double kThird = 1.0 / 3.0;
    shift = a * kThird;
    const double p = b - a * shift;
    const double q = (2.0 / 27.0) * a * a * a - a * b * kThird + c;
    half_q = 0.5 * q;
    third_p = p * kThird;
    disc = half_q * half_q + third_p * third_p * third_p;
  }
  // The one real root when disc > 0 (Cardano: t = u - (p/3) / u with u^3 taken with
  // the larger magnitude, w = -q/2 - sign(q) sqrt(disc), to avoid cancellation).
  // 1 / u comes with the inverse cube root, so there is no division.
  double single_root() const {
    const double w = -half_q - std::copysign(std::sqrt(disc), half_q);
    if (w == 0.0) return -shift;
    const double r = inverse_cube_root(w);
    return w * r * r - third_p * std::copysign(r, w) - shift;
  }
  // When disc <= 0: t = 2 m cos(phi - k 2pi/3), cos(3 phi) = -q / (2 m^3), m = sqrt(-p/3);
  // writes the first `count` (k = 0 is the largest root).
  void trigonometric_roots(int count, double* r) const {
    const double m = std::sqrt(-third_p);
    const double cos3 = m > 0.0 ? std::clamp(-half_q / (m * m * m), -1.0, 1.0) : 1.0;
    const double phi = std::acos(cos3) / 3.0;
    constexpr double kTwoPiThird = 2.0943951023931954923;
    for (int k = 0; k < count; ++k) r[k] = 2.0 * m * std::cos(phi - k * kTwoPiThird) - shift;
  }
  // The largest of the three when disc <= 0, without acos and cos: cos(phi) =
  // g(z) = cos(2/3 acos z) with z = cos(3 phi / 2) = sqrt((1 + cos 3 phi) / 2), phi in
  // [0, pi/3], is analytic on z in [0, 1]. g = 1/2 + z h(z) with h a degree-7 fit is
  // within 2e-8 z of it: near z = 0, where the two largest roots merge (1.15 z m
  // apart), the estimate stays much closer to the largest than to the middle one.
  double largest_trigonometric_root() const {
    const double m = std::sqrt(-third_p);
    if (!(m > 0.0)) return -shift;  // triple root
    const double m3 = m * m * m;
    const double z = std::sqrt(std::clamp((m3 - half_q) / (2.0 * m3), 0.0, 1.0));
    const double z2 = z * z, z4 = z2 * z2;
    // Estrin's scheme: shorter dependency chains than Horner's.
    const double h = ((0.5773502486759406 - 0.11110846868023369 * z) +
                      z2 * (0.05340106860747789 - 0.03243405975630165 * z)) +
                     z4 * ((0.020737759703903083 - 0.01163263943734725 * z) +
                           z2 * (0.004538893936568217 - 0.0008528144244822077 * z));
    return 2.0 * m * (0.5 + z * h) - shift;
  }
};

// The largest real root of x^3 + a x^2 + b x + c. Cardano's root is good to rounding
// but when the shift by a/3 cancels most of it; one step recovers that (measured: in
// 5 % of Lambda Twist's cubics). The trigonometric estimate (2e-8 relative) takes two.
double largest_root_of_monic_cubic(double a, double b, double c) {
  const std::array<double, 3> monic{a, b, c};
  const DepressedCubic cubic(a, b, c);
  if (cubic.disc > 0.0) {
    const double x = cubic.single_root();
    return std::abs(x) < 0.1 * std::abs(cubic.shift) ? newton_step<3>(monic, x) : x;
  }
  return newton_step<3>(monic, newton_step<3>(monic, cubic.largest_trigonometric_root()));
}

}  // namespace

int real_cubic_roots(double c3, double c2, double c1, double c0, std::array<double, 3>* roots) {
  const std::array<double, 3> monic{c2 / c3, c1 / c3, c0 / c3};
  const DepressedCubic cubic(monic[0], monic[1], monic[2]);
  auto& r = *roots;
  int n = 1;
  if (cubic.disc > 0.0) {
    r[0] = cubic.single_root();
  } else {
    n = 3;
    cubic.trigonometric_roots(n, r.data());
  }
  for (int i = 0; i < n; ++i) r[i] = polish<3>(monic, r[i]);
  std::sort(r.begin(), r.begin() + n);
  return n;
}

double largest_real_cubic_root(double c3, double c2, double c1, double c0) {
  const double inv = 1.0 / c3;
  return largest_root_of_monic_cubic(c2 * inv, c1 * inv, c0 * inv);
}

int real_quartic_roots(double c4, double c3, double c2, double c1, double c0, std::array<double, 4>* roots) {
  const double inv = 1.0 / c4;
  const double a = c3 * inv, b = c2 * inv, c = c1 * inv, d = c0 * inv;
  // x = y - a/4 gives the depressed quartic y^4 + p y^2 + q y + r = 0.
  const double shift = 0.25 * a, a2 = a * a;
  const double p = b - 3.0 / 8.0 * a2;
  const double q = c - 0.5 * a * b + 0.125 * a2 * a;
  const double r = d - 0.25 * a * c + a2 * b / 16.0 - 3.0 / 256.0 * a2 * a2;
  // Ferrari: (y^2 + p/2 + m)^2 = 2m y^2 - q y + m^2 + m p + p^2/4 - r is a square in y
  // when m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0; its largest root is the best conditioned.
  const double m = largest_root_of_monic_cubic(p, 0.25 * p * p - r, -0.125 * q * q);
  double y[4];
  int n = 0;
  if (m > 1e-12 * (std::abs(p) + std::sqrt(std::abs(r)))) {
    const double s = std::sqrt(2.0 * m);
    const double k = q / (2.0 * s);
    // y^2 - s y + p/2 + m + k = 0 and y^2 + s y + p/2 + m - k = 0, each with two real
    // roots or none: which one has them is data, so they are compacted by selects.
    double first[2], second[2];
    const bool has_first = real_quadratic_roots(-s, 0.5 * p + m + k, first) == 2;
    const bool has_second = real_quadratic_roots(s, 0.5 * p + m - k, second) == 2;
    y[0] = select_if(has_first, first[0], second[0]);
    y[1] = select_if(has_first, first[1], second[1]);
    y[2] = second[0], y[3] = second[1];
    n = 2 * (int(has_first) + int(has_second));
  } else {
    // q = 0: the biquadratic y^4 + p y^2 + r = 0.
    double z[2];
    if (real_quadratic_roots(p, r, z) == 2) {
      for (double zi : z) {
        if (zi < 0.0) {
          if (zi < -1e-12 * (std::abs(p) + std::sqrt(std::abs(r)))) continue;
          zi = 0.0;
        }
        y[n++] = std::sqrt(zi);
        y[n++] = -std::sqrt(zi);
      }
    }
  }
  const std::array<double, 4> monic{a, b, c, d};
  for (int i = 0; i < n; ++i) (*roots)[i] = polish<4>(monic, y[i] - shift);
  return n;
}

}  // namespace tetrapulse
