#include "tetrapulse/hardware/pose_conditioning.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "tetrapulse/hardware/view_directions.hpp"

namespace tetrapulse::hardware {

namespace {

Eigen::Vector3d centroid_of(const Markers& markers) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : markers) c += p / 4;
  return c;
}

}  // namespace

double target_radius(const Markers& markers) {
  const Eigen::Vector3d c = centroid_of(markers);
  double r = 0;
  for (const Eigen::Vector3d& p : markers) r = std::max(r, (p - c).norm());
  return r;
}

double view_conditioning(const Markers& markers, const Eigen::Vector3d& camera) {
  const Eigen::Vector3d c = centroid_of(markers);
  double rho2 = 0;
  for (const Eigen::Vector3d& p : markers) rho2 += (p - c).squaredNorm() / 4;
  const double rho = std::sqrt(rho2);
  // Camera frame: z towards the centroid; the roll about z does not change kappa.
  const Eigen::Vector3d z = (c - camera).normalized();
  const Eigen::Vector3d x = z.unitOrthogonal();
  Eigen::Matrix3d r;
  r.row(0) = x;
  r.row(1) = z.cross(x);
  r.row(2) = z;
  Eigen::Matrix<double, 8, 6> j;
  const Eigen::Vector3d c_cam = r * (c - camera);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d q = r * (markers[i] - camera);
    Eigen::Matrix<double, 2, 3> dproj;
    dproj << 1 / q.z(), 0, -q.x() / (q.z() * q.z()), 0, 1 / q.z(), -q.y() / (q.z() * q.z());
    Eigen::Matrix3d dq_domega;  // d(omega x (q - c)) / d omega = -[q - c]_x
    const Eigen::Vector3d a = q - c_cam;
    dq_domega << 0, a.z(), -a.y(), -a.z(), 0, a.x(), a.y(), -a.x(), 0;
    j.block<2, 3>(2 * i, 0) = dproj * dq_domega;
    j.block<2, 3>(2 * i, 3) = dproj * rho;
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 8, 6>> svd(j);
  const auto& s = svd.singularValues();
  return s[5] > 0 ? s[0] / s[5] : INFINITY;
}

PoseConditioning pose_conditioning(const Markers& markers, double marker_diameter, const ViewSphere& sphere) {
  PoseConditioning out;
  const Eigen::Vector3d c = centroid_of(markers);
  const std::vector<Eigen::Vector3d> views = fibonacci_directions(sphere.views, false);
  int overlapping = 0;
  std::vector<double> closest;
  closest.reserve(views.size());
  for (const Eigen::Vector3d& v : views) {
    const Eigen::Vector3d camera = c + sphere.distance * v;
    const double kappa = view_conditioning(markers, camera);
    if (kappa > out.worst_kappa) {
      out.worst_kappa = kappa;
      out.worst_direction = v;
    }
    if (v.z() >= 0) out.worst_kappa_above = std::max(out.worst_kappa_above, kappa);
    bool overlap = false;
    double nearest = INFINITY;
    for (const auto& e : kEdgeMarkers) {
      const Eigen::Vector3d a = markers[e[0]] - camera, b = markers[e[1]] - camera;
      const double separation = std::atan2(a.cross(b).norm(), a.dot(b));
      nearest = std::min(nearest, separation);
      const double radii = std::asin(std::min(1.0, marker_diameter / 2 / a.norm())) +
                           std::asin(std::min(1.0, marker_diameter / 2 / b.norm()));
      overlap = overlap || separation < radii;
    }
    overlapping += overlap ? 1 : 0;
    closest.push_back(nearest);
  }
  if (views.empty()) return out;
  out.overlap_fraction = static_cast<double>(overlapping) / views.size();
  std::nth_element(closest.begin(), closest.begin() + closest.size() / 2, closest.end());
  out.median_closest_rad = closest[closest.size() / 2];
  return out;
}

}  // namespace tetrapulse::hardware
