#pragma once
// Circles fitted to 2D points (pixels, or any unit: outputs share the inputs' unit).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace tetrapulse {

struct Circle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0;
};

// The circle through three points; nullopt when they are (nearly) collinear.
std::optional<Circle> circle_through(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// Algebraic least-squares circle (Kasa, IEEE Trans. Instrum. Meas. 25, 1976):
//   minimise  sum_i ( |p_i - c|^2 - r^2 )^2  over c, r.
// Exact for points on a circle; nullopt for fewer than 3 points or collinear ones.
std::optional<Circle> fit_circle_kasa(const Eigen::Vector2d* points, size_t count);

// Geometric least-squares circle: minimises  sum_i ( |p_i - c| - r )^2  by
// Gauss-Newton from `initial` (e.g. Kasa's circle, which shrinks towards the
// chord when the points cover only an arc). Nullopt when it does not converge.
std::optional<Circle> fit_circle_geometric(const Eigen::Vector2d* points, size_t count, const Circle& initial);

struct RobustCircleOptions {
  double inlier_tolerance = 0.75;  // | |p - c| - r | below this supports a circle
  int trials = 64;                 // random triples tried
  double min_radius = 0.5;
  double max_radius = 1e9;
  uint32_t seed = 1;               // the triples are a deterministic function of the seed
};

struct RobustCircle {
  Circle circle;
  int inliers = 0;  // points within inlier_tolerance of the refined circle
};

// The circle supported by the most points (RANSAC over triples), refined by
// Kasa's then the geometric fit on its supporters: finds a rim among points of which some lie
// elsewhere (the chord of a cut disc). `inlier` (optional) receives one flag a
// point. Nullopt when no triple gives a circle within the radius bounds.
std::optional<RobustCircle> fit_circle_robust(const Eigen::Vector2d* points, size_t count,
                                              const RobustCircleOptions& options,
                                              std::vector<uint8_t>* inlier = nullptr);

}  // namespace tetrapulse
