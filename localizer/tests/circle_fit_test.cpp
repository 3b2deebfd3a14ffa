#include "tetrapulse/localizer/circle_fit.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tetrapulse {
namespace {

std::vector<Eigen::Vector2d> arc(const Circle& c, double from, double to, int n, double noise, std::mt19937* rng) {
  std::normal_distribution<double> g(0, noise);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = from + (to - from) * i / std::max(n - 1, 1);
    pts.push_back(c.center + (c.radius + (noise > 0 ? g(*rng) : 0.0)) * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pts;
}

TEST(CircleFit, ThroughThreePointsAndCollinearOnes) {
  const auto c = circle_through({1, 0}, {0, 1}, {-1, 0});
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->center.norm(), 0, 1e-12);
  EXPECT_NEAR(c->radius, 1, 1e-12);
  EXPECT_FALSE(circle_through({0, 0}, {1, 1}, {2, 2}));
  EXPECT_FALSE(circle_through({0, 0}, {0, 0}, {2, 2}));
}

TEST(CircleFit, KasaAndGeometricAreExactOnPointsOfACircle) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-100, 100), r(0.5, 50), a(0, 2 * M_PI);
  for (int trial = 0; trial < 200; ++trial) {
    const Circle truth{{u(rng), u(rng)}, r(rng)};
    const double from = a(rng);
    const auto pts = arc(truth, from, from + 1.0 + 5.0 * (trial % 5) / 4.0, 12, 0, &rng);
    const auto kasa = fit_circle_kasa(pts.data(), pts.size());
    ASSERT_TRUE(kasa);
    EXPECT_LT((kasa->center - truth.center).norm(), 1e-6 * truth.radius);
    const auto geo = fit_circle_geometric(pts.data(), pts.size(), Circle{kasa->center + Eigen::Vector2d(0.3, -0.2), kasa->radius * 1.1});
    ASSERT_TRUE(geo);
    EXPECT_LT((geo->center - truth.center).norm(), 1e-6 * truth.radius);
    EXPECT_NEAR(geo->radius, truth.radius, 1e-6 * truth.radius);
  }
  const std::vector<Eigen::Vector2d> line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_FALSE(fit_circle_kasa(line.data(), line.size()));
  EXPECT_FALSE(fit_circle_kasa(line.data(), 2));
}

TEST(CircleFit, GeometricFitRemovesKasasShrinkageOnANoisyArc) {
  std::mt19937 rng(4);
  double kasa_err = 0, geo_err = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Circle truth{{10, 20}, 6};
    const auto pts = arc(truth, 0.2, 0.2 + M_PI / 2, 30, 0.15, &rng);
    const auto kasa = fit_circle_kasa(pts.data(), pts.size());
    ASSERT_TRUE(kasa);
    const auto geo = fit_circle_geometric(pts.data(), pts.size(), *kasa);
    ASSERT_TRUE(geo);
    kasa_err += kasa->radius - truth.radius;
    geo_err += geo->radius - truth.radius;
  }
  EXPECT_LT(kasa_err / 100, -0.05);  // Kasa's known bias on a short arc
  EXPECT_LT(std::abs(geo_err / 100), 0.5 * std::abs(kasa_err / 100));
}

TEST(CircleFit, RobustFitIgnoresTheChordOfACutDisc) {
  std::mt19937 rng(9);
  int bad = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Circle truth{{50.3, 40.7}, 5.0 + trial % 7};
    // The upper half's rim, and the cut along the diameter.
    auto pts = arc(truth, M_PI, 2 * M_PI, 40, 0.05, &rng);
    for (int i = 1; i < 15; ++i) pts.push_back(truth.center + Eigen::Vector2d(truth.radius * (-1 + 2.0 * i / 15), 0));
    std::vector<uint8_t> inlier;
    const auto fit = fit_circle_robust(pts.data(), pts.size(), RobustCircleOptions{0.35, 64, 0.5, 100, 1}, &inlier);
    ASSERT_TRUE(fit);
    bad += (fit->circle.center - truth.center).norm() > 0.1;  // about 5 sigma of the fit with this noise
    int chord_inliers = 0;
    for (size_t i = 40; i < pts.size(); ++i) chord_inliers += inlier[i];
    EXPECT_LE(chord_inliers, 2);  // only chord points at the rim itself may fit
    EXPECT_GE(fit->inliers, 38);
  }
  EXPECT_EQ(bad, 0);
}

}  // namespace
}  // namespace tetrapulse
