#include "tetrapulse/hardware/tetrahedron.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse::hardware {

namespace {

double signed_sqrt(double x) { return x >= 0 ? std::sqrt(x) : -std::sqrt(-x); }

}  // namespace

Edges edges_of(const Markers& m) {
  Edges e{};
  for (int k = 0; k < 6; ++k) e[k] = (m[kEdgeMarkers[k][0]] - m[kEdgeMarkers[k][1]]).norm();
  return e;
}

double triangle_area(double a, double b, double c) {
  // Kahan: sort a >= b >= c, then 16 A^2 = (a+(b+c)) (c-(a-b)) (c+(a-b)) (a+(b-c)).
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  return 0.25 * signed_sqrt((a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c)));
}

double tetrahedron_volume(const Edges& e) {
  const double u2 = e[0] * e[0], v2 = e[1] * e[1], w2 = e[2] * e[2];
  const double g12 = 0.5 * (u2 + v2 - e[3] * e[3]);  // p1.p2 with p0 at the origin
  const double g13 = 0.5 * (u2 + w2 - e[4] * e[4]);
  const double g23 = 0.5 * (v2 + w2 - e[5] * e[5]);
  const double det = u2 * v2 * w2 + 2 * g12 * g13 * g23 - u2 * g23 * g23 - v2 * g13 * g13 - w2 * g12 * g12;
  return signed_sqrt(det) / 6.0;
}

std::array<double, 4> face_heights(const Edges& e) {
  const double volume = tetrahedron_volume(e);
  std::array<double, 4> h{};
  for (int k = 0; k < 4; ++k) {
    const auto& f = kFaceEdges[k];
    // A degenerate face makes the altitude undefined; treat it as flat (height 0).
    const double area = triangle_area(e[f[0]], e[f[1]], e[f[2]]);
    h[k] = area > 1e-300 ? 3.0 * volume / area : std::min(0.0, volume);
  }
  return h;
}

double min_face_height(const Edges& e) {
  const auto h = face_heights(e);
  return *std::min_element(h.begin(), h.end());
}

double min_triangle_altitude(const Edges& e) {
  double best = INFINITY;
  for (const auto& f : kFaceEdges) {
    const double area = triangle_area(e[f[0]], e[f[1]], e[f[2]]);
    for (int s : f) best = std::min(best, e[s] > 0 ? 2.0 * area / e[s] : 0.0);
  }
  return best;
}

Markers embed(const Edges& e) {
  const double a = e[0], b = e[1], c = e[2], f = e[3], en = e[4], d = e[5];
  Markers m{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  m[0] = Eigen::Vector3d::Zero();
  m[1] = Eigen::Vector3d(a, 0, 0);
  if (!(a > 0)) return m;  // no edge to build on: all markers at the origin
  const double x2 = (a * a + b * b - f * f) / (2 * a);
  const double y2 = std::sqrt(std::max(0.0, b * b - x2 * x2));
  m[2] = Eigen::Vector3d(x2, y2, 0);
  const double x3 = (a * a + c * c - en * en) / (2 * a);
  const double y3 = y2 > 0 ? (c * c + b * b - d * d - 2 * x2 * x3) / (2 * y2) : 0.0;
  m[3] = Eigen::Vector3d(x3, y3, std::sqrt(std::max(0.0, c * c - x3 * x3 - y3 * y3)));
  return m;
}

Edges projected_edges(const Markers& markers, const Eigen::Vector3d& up) {
  Edges e{};
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d v = markers[kEdgeMarkers[k][0]] - markers[kEdgeMarkers[k][1]];
    e[k] = (v - up.dot(v) * up).norm();
  }
  return e;
}

double volume_ratio(const Edges& e) {
  double sum2 = 0;
  for (double d : e) sum2 += d * d;
  const double l = std::sqrt(sum2 / 6.0);
  const double regular = l * l * l / (6.0 * std::sqrt(2.0));
  return regular > 0 ? tetrahedron_volume(e) / regular : 0.0;
}

}  // namespace tetrapulse::hardware
