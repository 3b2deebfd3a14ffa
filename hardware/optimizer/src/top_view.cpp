#include "tetrapulse/hardware/top_view.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "block_ascent.hpp"
#include "tetrapulse/hardware/view_directions.hpp"

namespace tetrapulse::hardware {

namespace {

constexpr int kScanDirections = 64;  // starts scanned per target before each of its simplices

Eigen::VectorXd angles_of(const Eigen::Vector3d& up) {
  Eigen::VectorXd x(2);
  x << std::acos(std::clamp(up.z(), -1.0, 1.0)), std::atan2(up.y(), up.x());
  return x;
}

TargetShape projection_shape(const Markers& markers, const Eigen::Vector3d& up) {
  return planar_shape(projected_edges(markers, up));
}

}  // namespace

Eq1Limits default_top_view_limits(const Eq1Limits& limits) {
  return Eq1Limits{limits.d1 / 2, limits.d2, limits.h / 2, limits.w};
}

std::vector<TargetShape> top_view_shapes(const std::vector<Markers>& targets, const std::vector<Eigen::Vector3d>& up) {
  std::vector<TargetShape> shapes;
  for (size_t i = 0; i < targets.size() && i < up.size(); ++i) shapes.push_back(projection_shape(targets[i], up[i]));
  return shapes;
}

TopView best_top_view(const std::vector<Markers>& targets, const Eq1Limits& top) {
  const TargetModel model = [&](int index, const Eigen::VectorXd& x) {
    return projection_shape(targets[static_cast<size_t>(index)], direction_from_angles(x[0], x[1]));
  };
  // Up and down give the same projection: half the sphere holds every view.
  const std::vector<Eigen::Vector3d> scan = fibonacci_directions(kScanDirections, true);
  const SweepStart scan_start = [&](int, const Eigen::VectorXd& current, const Objective& f) {
    Eigen::VectorXd best = current;
    double best_f = f(current);
    for (const Eigen::Vector3d& d : scan) {
      const Eigen::VectorXd x = angles_of(d);
      const double v = f(x);
      if (v > best_f) {
        best_f = v;
        best = x;
      }
    }
    return best;
  };
  std::vector<Eigen::VectorXd> params(targets.size(), angles_of(Eigen::Vector3d::UnitZ()));
  BlockAscentOptions options;
  options.simplex.step = 0.2;  // radians
  options.simplex.x_tolerance = 1e-9;
  TopView view;
  view.score = block_ascent(model, top, options, &params, scan_start);
  for (const Eigen::VectorXd& x : params) view.up.push_back(direction_from_angles(x[0], x[1]));
  return view;
}

Markers place_on_support(const Markers& markers, const Eigen::Vector3d& up, double lift) {
  const Eigen::Vector3d z = up.normalized();
  // Turn about z so that marker 0 -> marker 1 projects onto +y (as in the paper's target).
  Eigen::Vector3d y = markers[1] - markers[0];
  y -= z.dot(y) * z;
  if (y.norm() < 1e-12) y = z.unitOrthogonal();
  y.normalize();
  Eigen::Matrix3d rows;
  rows.row(0) = y.cross(z);
  rows.row(1) = y;
  rows.row(2) = z;
  Markers out;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    out[i] = rows * markers[i];
    centroid += out[i] / 4;
  }
  double z_min = INFINITY;
  for (const Eigen::Vector3d& p : out) z_min = std::min(z_min, p.z());
  for (Eigen::Vector3d& p : out) p -= Eigen::Vector3d(centroid.x(), centroid.y(), z_min - lift);
  return out;
}

}  // namespace tetrapulse::hardware
