#include "tetrapulse/localizer/polynomial_roots.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

namespace tetrapulse {
namespace {

// Coefficients (highest degree first) of scale * prod (x - r_k) over complex roots
// that come in conjugate pairs, so the coefficients are real.
std::vector<double> expand(double scale, const std::vector<std::complex<double>>& roots) {
  std::vector<std::complex<double>> c{scale};
  for (const auto& r : roots) {
    c.push_back(0);
    for (size_t i = c.size() - 1; i > 0; --i) c[i] -= r * c[i - 1];
  }
  std::vector<double> out;
  for (const auto& v : c) out.push_back(v.real());
  return out;
}

// Largest distance from a wanted root to the nearest found one, relative to the roots' scale.
double worst_miss(const std::vector<double>& wanted, const double* found, int n) {
  double scale = 1, worst = 0;
  for (double w : wanted) scale = std::max(scale, std::abs(w));
  for (double w : wanted) {
    double nearest = INFINITY;
    for (int i = 0; i < n; ++i) nearest = std::min(nearest, std::abs(found[i] - w));
    worst = std::max(worst, nearest / scale);
  }
  return worst;
}

TEST(PolynomialRoots, CubicFindsAllRealRootsAndOnlyThose) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 10000; ++i) {
    const double scale = u(rng);
    std::array<double, 3> roots;
    if (i % 2 == 0) {
      const std::vector<double> r{u(rng), u(rng), u(rng)};
      const auto c = expand(scale, {r[0], r[1], r[2]});
      ASSERT_EQ(real_cubic_roots(c[0], c[1], c[2], c[3], &roots), 3);
      EXPECT_LT(worst_miss(r, roots.data(), 3), 1e-7);  // close roots lose digits, as they must
      EXPECT_TRUE(std::is_sorted(roots.begin(), roots.end()));
    } else {
      const double r = u(rng);
      const std::complex<double> z{u(rng), 0.1 + std::abs(u(rng))};
      const auto c = expand(scale, {r, z, std::conj(z)});
      ASSERT_EQ(real_cubic_roots(c[0], c[1], c[2], c[3], &roots), 1);
      EXPECT_LT(worst_miss({r}, roots.data(), 1), 1e-12);
    }
  }
}

TEST(PolynomialRoots, LargestCubicRootIsTheLastOfAll) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 10000; ++i) {
    const double c3 = u(rng), c2 = u(rng), c1 = u(rng), c0 = u(rng);
    std::array<double, 3> roots;
    const int n = real_cubic_roots(c3, c2, c1, c0, &roots);
    const double largest = largest_real_cubic_root(c3, c2, c1, c0);
    EXPECT_NEAR(largest, roots[n - 1], 1e-9 * (1 + std::abs(largest)));
  }
}

TEST(PolynomialRoots, QuarticFindsFourTwoOrNoRealRoots) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int i = 0; i < 10000; ++i) {
    const double scale = u(rng);
    const std::complex<double> z{u(rng), 0.1 + std::abs(u(rng))}, w{u(rng), 0.1 + std::abs(u(rng))};
    std::vector<double> real;
    std::vector<std::complex<double>> all;
    const int real_count = 2 * (i % 3);  // 0, 2 or 4
    for (int k = 0; k < real_count; ++k) real.push_back(u(rng));
    all.assign(real.begin(), real.end());
    if (real_count <= 2) all.insert(all.end(), {z, std::conj(z)});
    if (real_count == 0) all.insert(all.end(), {w, std::conj(w)});
    const auto c = expand(scale, all);
    std::array<double, 4> roots;
    const int n = real_quartic_roots(c[0], c[1], c[2], c[3], c[4], &roots);
    ASSERT_EQ(n, real_count) << "case " << i;
    if (n > 0) {
      EXPECT_LT(worst_miss(real, roots.data(), n), 1e-6) << "case " << i;
    }
  }
}

TEST(PolynomialRoots, QuarticKeepsADoubleRoot) {
  // (x - 0.3)^2 (x + 1)(x - 2): the tangency must not vanish in rounding.
  const auto c = expand(1.7, {0.3, 0.3, -1.0, 2.0});
  std::array<double, 4> roots;
  const int n = real_quartic_roots(c[0], c[1], c[2], c[3], c[4], &roots);
  ASSERT_GE(n, 3);
  EXPECT_LT(worst_miss({0.3, -1.0, 2.0}, roots.data(), n), 1e-7);
}

TEST(PolynomialRoots, BiquadraticQuartic) {
  // x^4 - 5 x^2 + 4 = (x^2 - 1)(x^2 - 4): q = 0 in Ferrari's depressed form.
  std::array<double, 4> roots;
  ASSERT_EQ(real_quartic_roots(1, 0, -5, 0, 4, &roots), 4);
  EXPECT_LT(worst_miss({-2, -1, 1, 2}, roots.data(), 4), 1e-14);
}

TEST(PolynomialRoots, LargestCubicRootWhenTheTwoLargestMerge) {
  // (x - s (1 + delta))(x - s)(x + 30 s): the largest root and the middle one meet as
  // delta goes to 0 while the third stays far away, as in Lambda Twist's cubic near the
  // danger cylinder. The root returned must be the largest, much closer to it than to
  // the middle one.
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  for (int e = 1; e <= 6; ++e) {
    const double delta = std::pow(10.0, -e);
    for (int i = 0; i < 1000; ++i) {
      const double scale = u(rng) * (i % 2 ? 1 : -1), size = u(rng);
      const auto c = expand(scale, {size * (1 + delta), size, -30 * size});
      const double largest = largest_real_cubic_root(c[0], c[1], c[2], c[3]);
      EXPECT_LT(std::abs(largest - size * (1 + delta)), 0.01 * delta * size) << "delta " << delta;
    }
  }
}

TEST(PolynomialRoots, SingleCubicRootOverNinetyOrdersOfMagnitude) {
  // One real root r and a complex pair of the same magnitude, r from 1e-45 to 1e45 (the
  // discriminant goes with r^6): Cardano's cube root must hold its precision at every
  // exponent.
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int e = -45; e <= 45; ++e) {
    for (int i = 0; i < 20; ++i) {
      const double size = std::pow(10.0, e + u(rng));
      const double r = size * (u(rng) < 0 ? -1 : 1);
      const std::complex<double> z{size * u(rng), size * (0.1 + std::abs(u(rng)))};
      const auto c = expand(1.0 + u(rng) * 0.5, {r, z, std::conj(z)});
      std::array<double, 3> roots;
      ASSERT_EQ(real_cubic_roots(c[0], c[1], c[2], c[3], &roots), 1) << "e " << e;
      EXPECT_LT(std::abs(roots[0] - r), 1e-12 * size) << "e " << e;
      EXPECT_LT(std::abs(largest_real_cubic_root(c[0], c[1], c[2], c[3]) - r), 1e-12 * size) << "e " << e;
    }
  }
}

}  // namespace
}  // namespace tetrapulse
