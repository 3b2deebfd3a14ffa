#include "tetrapulse/localizer/testing/p3p_problems.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace tetrapulse::testing {
namespace {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<Vec3, 3>;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3{g(rng), g(rng), g(rng)}.normalized();  // braces: evaluated in order
}

// A point in front of the camera, within `half_angle` of the optical axis, at
// distance [near, far].
Vec3 random_point_in_view(std::mt19937_64& rng, double half_angle, double near, double far) {
  const double cos_max = std::cos(half_angle);
  const double z = uniform(rng, cos_max, 1.0);  // uniform over the spherical cap
  const double phi = uniform(rng, 0, 2 * M_PI);
  const double r = std::sqrt(1 - z * z);
  return uniform(rng, near, far) * Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

double smallest_angle(const Triangle& p) {
  double smallest = M_PI;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  return smallest;
}

// Circumcircle centre and radius, and the plane normal, of a triangle.
void circumcircle(const Triangle& p, Vec3* centre, double* radius, Vec3* normal) {
  const Vec3 u = p[1] - p[0], v = p[2] - p[0], w = u.cross(v);
  *centre = p[0] + (u.squaredNorm() * v - v.squaredNorm() * u).cross(w) / (2 * w.squaredNorm());
  *radius = (*centre - p[0]).norm();
  *normal = w.normalized();
}

// Away from the danger cylinder and from the triangle's plane, both by 20 % of
// the circumradius; triangle angles at least 15 degrees.
bool well_conditioned(const Triangle& p) {
  if (smallest_angle(p) < 15 * M_PI / 180) return false;
  Vec3 c, n;
  double rc;
  circumcircle(p, &c, &rc, &n);
  const Vec3 to_camera = -c;  // the camera is at the origin
  const double height = std::abs(n.dot(to_camera));
  const double from_axis = (to_camera - n * n.dot(to_camera)).norm();
  return height > 0.2 * rc && std::abs(from_axis - rc) > 0.2 * rc;
}

Triangle well_conditioned_triangle(std::mt19937_64& rng) {
  for (;;) {
    const Triangle p{random_point_in_view(rng, M_PI / 4, 0.5, 5), random_point_in_view(rng, M_PI / 4, 0.5, 5),
                     random_point_in_view(rng, M_PI / 4, 0.5, 5)};
    if (well_conditioned(p)) return p;
  }
}

Triangle near_collinear_triangle(std::mt19937_64& rng, double offset) {
  for (;;) {
    const Vec3 p1 = random_point_in_view(rng, M_PI / 4, 0.5, 5), p2 = random_point_in_view(rng, M_PI / 4, 0.5, 5);
    const Vec3 d = p2 - p1;
    if (d.norm() < 0.3) continue;
    const Vec3 across = d.cross(random_unit(rng)).normalized();
    const Vec3 p3 = p1 + uniform(rng, 0.25, 0.75) * d + offset * d.norm() * across;
    if (p3.z() > 0.3) return {p1, p2, p3};
  }
}

Triangle near_danger_cylinder_triangle(std::mt19937_64& rng, double offset) {
  for (;;) {
    // Target frame: the points on a circle of radius rc in z = 0; the camera at
    // (1 + offset) rc from the axis, looking at the triangle's centroid.
    const double rc = uniform(rng, 0.1, 0.5);
    Triangle P;
    for (auto& p : P) {
      const double a = uniform(rng, 0, 2 * M_PI);
      p = Vec3(rc * std::cos(a), rc * std::sin(a), 0);
    }
    if (smallest_angle(P) < 15 * M_PI / 180) continue;
    const double psi = uniform(rng, 0, 2 * M_PI);
    const Vec3 C((1 + offset) * rc * std::cos(psi), (1 + offset) * rc * std::sin(psi), uniform(rng, 0.5, 3) * rc);
    const Vec3 z = ((P[0] + P[1] + P[2]) / 3 - C).normalized();
    const Vec3 x = z.cross(random_unit(rng)).normalized();
    Eigen::Matrix3d R_CT;  // rows: camera axes in the target frame
    R_CT.row(0) = x;
    R_CT.row(1) = z.cross(x);
    R_CT.row(2) = z;
    Triangle p;
    bool in_view = true;
    for (int i = 0; i < 3; ++i) {
      p[i] = R_CT * (P[i] - C);
      in_view = in_view && p[i].z() > std::cos(70 * M_PI / 180) * p[i].norm();
    }
    if (in_view) return p;
  }
}

Triangle small_far_triangle(std::mt19937_64& rng, double side) {
  for (;;) {
    Triangle p{random_unit(rng), random_unit(rng), random_unit(rng)};
    if (smallest_angle(p) < 20 * M_PI / 180) continue;
    const double longest = std::max({(p[0] - p[1]).norm(), (p[0] - p[2]).norm(), (p[1] - p[2]).norm()});
    const Vec3 centre = random_point_in_view(rng, 40 * M_PI / 180, 3, 3);
    const Vec3 mean = (p[0] + p[1] + p[2]) / 3;
    for (auto& q : p) q = centre + (q - mean) * (side / longest);
    return p;
  }
}

}  // namespace

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond{g(rng), g(rng), g(rng), g(rng)}.normalized().toRotationMatrix();
}

P3PProblem random_p3p_problem(std::mt19937_64& rng, P3PCondition condition, double level) {
  Triangle p;
  switch (condition) {
    case P3PCondition::kWell: p = well_conditioned_triangle(rng); break;
    case P3PCondition::kNearCollinear: p = near_collinear_triangle(rng, level); break;
    case P3PCondition::kNearDangerCylinder: p = near_danger_cylinder_triangle(rng, level); break;
    case P3PCondition::kSmallFar: p = small_far_triangle(rng, level); break;
  }
  // A random target frame whose origin lies near its points, as a real target's does.
  const double size = std::max({(p[0] - p[1]).norm(), (p[0] - p[2]).norm(), (p[1] - p[2]).norm()});
  P3PProblem problem;
  problem.truth.R = random_rotation(rng);
  problem.truth.t = (p[0] + p[1] + p[2]) / 3 + size * Vec3{uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5),
                                                           uniform(rng, -0.5, 0.5)};
  for (int i = 0; i < 3; ++i) {
    problem.X[i] = problem.truth.R.transpose() * (p[i] - problem.truth.t);
    problem.x[i] = p[i].normalized();
  }
  return problem;
}

double pose_error(const Pose& pose, const Pose& truth) {
  return std::max(rotation_angle_between(pose.R, truth.R), (pose.t - truth.t).norm() / truth.t.norm());
}

double best_pose_error(const PoseCandidates& poses, int n, const Pose& truth) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) best = std::min(best, pose_error(poses[i], truth));
  return best;
}

}  // namespace tetrapulse::testing
