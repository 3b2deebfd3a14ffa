#include "tetrapulse/localizer/polynomial_roots.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {
namespace {

// Newton steps on a monic polynomial (coefficients c[0..n-1] of x^(n-1)..x^0
// below the leading 1); a step is kept only when it lowers |p(x)|.
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
  for (int it = 0; it < 2 && f != 0.0; ++it) {
    if (!(std::abs(d) > 0.0)) break;
    const double next = x - f / d;
    double dn;
    const double fn = eval(next, &dn);
    if (!(std::abs(fn) < std::abs(f))) break;
    x = next, f = fn, d = dn;
  }
  return x;
}

// Real roots of y^2 + B y + C = 0. A slightly negative discriminant (rounding of
// a double root) counts as zero.
int real_quadratic_roots(double B, double C, double* y) {
  double disc = B * B - 4.0 * C;
  if (disc < 0.0) {
    if (disc < -1e-12 * (B * B + 4.0 * std::abs(C))) return 0;
    disc = 0.0;
  }
  // The root without cancellation first; the other from the product of the roots.
  const double big = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  y[0] = big;
  y[1] = big != 0.0 ? C / big : 0.0;
  return 2;
}

// x^3 + a x^2 + b x + c = 0 with x = t - a/3 becomes t^3 + p t + q = 0.
struct DepressedCubic {
  double shift, third_p, half_q, disc;

  DepressedCubic(double a, double b, double c) {
    shift = a / 3.0;
    const double p = b - a * shift;
    const double q = (2.0 / 27.0) * a * a * a - a * b / 3.0 + c;
    half_q = q / 2.0;
    third_p = p / 3.0;
    disc = half_q * half_q + third_p * third_p * third_p;
  }
  // The one real root when disc > 0 (Cardano; u^3 taken with the larger magnitude
  // to avoid cancellation).
  double single_root() const {
    const double u = std::cbrt(-half_q - std::copysign(std::sqrt(disc), half_q));
    return (u != 0.0 ? u - third_p / u : 0.0) - shift;
  }
  // When disc <= 0: t = 2 m cos(phi - k 2pi/3), cos(3 phi) = -q / (2 m^3), m = sqrt(-p/3);
  // writes the first `count` (k = 0 is the largest root).
  void trigonometric_roots(int count, double* r) const {
    const double m = std::sqrt(-third_p);
    const double cos3 = m > 0.0 ? std::clamp(-half_q / (m * m * m), -1.0, 1.0) : 1.0;
    const double phi = std::acos(cos3) / 3.0;
    constexpr double kThird = 2.0943951023931954923;  // 2 pi / 3
    for (int k = 0; k < count; ++k) r[k] = 2.0 * m * std::cos(phi - k * kThird) - shift;
  }
};

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
  const std::array<double, 3> monic{c2 / c3, c1 / c3, c0 / c3};
  const DepressedCubic cubic(monic[0], monic[1], monic[2]);
  double r;
  if (cubic.disc > 0.0) {
    r = cubic.single_root();
  } else {
    cubic.trigonometric_roots(1, &r);
  }
  return polish<3>(monic, r);
}

int real_quartic_roots(double c4, double c3, double c2, double c1, double c0, std::array<double, 4>* roots) {
  const double a = c3 / c4, b = c2 / c4, c = c1 / c4, d = c0 / c4;
  // x = y - a/4 gives the depressed quartic y^4 + p y^2 + q y + r = 0.
  const double shift = a / 4.0, a2 = a * a;
  const double p = b - 3.0 / 8.0 * a2;
  const double q = c - a * b / 2.0 + a2 * a / 8.0;
  const double r = d - a * c / 4.0 + a2 * b / 16.0 - 3.0 / 256.0 * a2 * a2;
  // Ferrari: (y^2 + p/2 + m)^2 = 2m y^2 - q y + m^2 + m p + p^2/4 - r is a square in y
  // when 8 m^3 + 8 p m^2 + (2 p^2 - 8 r) m - q^2 = 0; its largest root is the best conditioned.
  const double m = largest_real_cubic_root(8.0, 8.0 * p, 2.0 * p * p - 8.0 * r, -q * q);
  double y[4];
  int n = 0;
  if (m > 1e-12 * (std::abs(p) + std::sqrt(std::abs(r)))) {
    const double s = std::sqrt(2.0 * m);
    const double k = q / (2.0 * s);
    n += real_quadratic_roots(-s, p / 2.0 + m + k, y + n);
    n += real_quadratic_roots(s, p / 2.0 + m - k, y + n);
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
