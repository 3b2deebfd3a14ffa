#include "tetrapulse/localizer/circle_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace tetrapulse {

std::optional<Circle> circle_through(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  // Centre x solves 2 (b - a) . x = |b|^2 - |a|^2 and 2 (c - a) . x = |c|^2 - |a|^2.
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double det = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  const double scale = ab.squaredNorm() * ac.squaredNorm();
  if (!(det * det > 1e-12 * scale)) return std::nullopt;  // also catches coincident points
  const double r1 = ab.squaredNorm(), r2 = ac.squaredNorm();
  const Eigen::Vector2d offset((ac.y() * r1 - ab.y() * r2) / det, (ab.x() * r2 - ac.x() * r1) / det);
  return Circle{a + offset, offset.norm()};
}

std::optional<Circle> fit_circle_kasa(const Eigen::Vector2d* points, size_t count) {
  if (count < 3) return std::nullopt;
  // Centred coordinates keep the normal equations well conditioned.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < count; ++i) mean += points[i];
  mean /= double(count);
  // |q|^2 + D qx + E qy + F = 0 in least squares, q = p - mean.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < count; ++i) {
    const Eigen::Vector2d q = points[i] - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1.0);
    A += row * row.transpose();
    rhs -= row * q.squaredNorm();
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::Vector3d s = ldlt.solve(rhs);
  if (!s.allFinite()) return std::nullopt;
  const Eigen::Vector2d c(-0.5 * s.x(), -0.5 * s.y());
  const double r2 = c.squaredNorm() - s.z();
  // Collinear points give a huge or imaginary circle.
  double spread = 0;
  for (size_t i = 0; i < count; ++i) spread = std::max(spread, (points[i] - mean).squaredNorm());
  if (!(r2 > 0) || r2 > 1e12 * std::max(spread, 1e-300)) return std::nullopt;
  return Circle{c + mean, std::sqrt(r2)};
}

std::optional<Circle> fit_circle_geometric(const Eigen::Vector2d* points, size_t count, const Circle& initial) {
  if (count < 3) return std::nullopt;
  Eigen::Vector3d x(initial.center.x(), initial.center.y(), initial.radius);
  for (int iter = 0; iter < 20; ++iter) {
    // Residual d_i = |p_i - c| - r; its gradient is (-(p_i - c) / |p_i - c|, -1).
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < count; ++i) {
      const Eigen::Vector2d d = points[i] - x.head<2>();
      const double n = d.norm();
      if (n < 1e-12) continue;
      const Eigen::Vector3d J(-d.x() / n, -d.y() / n, -1.0);
      JtJ += J * J.transpose();
      Jtr += J * (n - x.z());
    }
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(JtJ);
    if (ldlt.info() != Eigen::Success) return std::nullopt;
    const Eigen::Vector3d step = ldlt.solve(-Jtr);
    if (!step.allFinite()) return std::nullopt;
    x += step;
    if (step.norm() < 1e-10 * std::max(1.0, std::abs(x.z()))) break;
  }
  if (!x.allFinite() || !(x.z() > 0)) return std::nullopt;
  return Circle{x.head<2>(), x.z()};
}

namespace {

int count_inliers(const Eigen::Vector2d* points, size_t count, const Circle& c, double tolerance,
                  std::vector<uint8_t>* flags) {
  int n = 0;
  for (size_t i = 0; i < count; ++i) {
    const bool in = std::abs((points[i] - c.center).norm() - c.radius) <= tolerance;
    n += in;
    if (flags) (*flags)[i] = in;
  }
  return n;
}

// A small deterministic generator: the same points always give the same circle.
uint32_t next_random(uint32_t* state) {
  *state ^= *state << 13;
  *state ^= *state >> 17;
  *state ^= *state << 5;
  return *state;
}

}  // namespace

std::optional<RobustCircle> fit_circle_robust(const Eigen::Vector2d* points, size_t count,
                                              const RobustCircleOptions& options, std::vector<uint8_t>* inlier) {
  if (count < 3) return std::nullopt;
  const auto plausible = [&](const Circle& c) {
    return std::isfinite(c.radius) && c.radius >= options.min_radius && c.radius <= options.max_radius;
  };
  uint32_t state = options.seed == 0 ? 0x9e3779b9u : options.seed;
  std::optional<Circle> best;
  int best_count = 0;
  const uint32_t n = static_cast<uint32_t>(count);
  for (int t = 0; t < options.trials; ++t) {
    const uint32_t i = next_random(&state) % n, j = next_random(&state) % n, k = next_random(&state) % n;
    if (i == j || j == k || i == k) continue;
    const auto c = circle_through(points[i], points[j], points[k]);
    if (!c || !plausible(*c)) continue;
    const int support = count_inliers(points, count, *c, options.inlier_tolerance, nullptr);
    if (support > best_count) {
      best_count = support;
      best = c;
    }
  }
  if (!best) return std::nullopt;
  // Refine on the supporters, then on a band that shrinks to 2.5 times their
  // RMS distance from the circle: points just off the rim (the ends of a
  // chord) would otherwise pull it.
  std::vector<uint8_t> local;
  std::vector<uint8_t>& flags = inlier ? *inlier : local;
  flags.assign(count, 0);
  Circle circle = *best;
  double band = options.inlier_tolerance;
  std::vector<Eigen::Vector2d> support;
  for (int round = 0; round < 4; ++round) {
    count_inliers(points, count, circle, band, &flags);
    support.clear();
    for (size_t i = 0; i < count; ++i)
      if (flags[i]) support.push_back(points[i]);
    auto refined = round == 0 ? fit_circle_kasa(support.data(), support.size()) : std::optional<Circle>(circle);
    if (refined) refined = fit_circle_geometric(support.data(), support.size(), *refined);
    if (!refined || !plausible(*refined)) break;
    circle = *refined;
    double sum2 = 0;
    for (const auto& p : support) sum2 += std::pow((p - circle.center).norm() - circle.radius, 2);
    const double rms = std::sqrt(sum2 / double(support.size()));
    band = std::clamp(2.5 * rms, 0.1 * options.inlier_tolerance, options.inlier_tolerance);
  }
  const int final_count = count_inliers(points, count, circle, options.inlier_tolerance, &flags);
  return RobustCircle{circle, final_count};
}

}  // namespace tetrapulse
