#include "tetrapulse/hardware/target_analysis.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "tetrapulse/hardware/top_view.hpp"
#include "number_text.hpp"

namespace tetrapulse::hardware {

namespace {

constexpr std::array<const char*, 6> kEdgeNames{"d01", "d02", "d03", "d12", "d13", "d23"};
constexpr std::array<const char*, 4> kHeightNames{"h0", "h1", "h2", "h3"};

double flatness_of(const Markers& markers) {
  Eigen::Matrix<double, 4, 3> centred;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : markers) c += p / 4;
  for (int i = 0; i < 4; ++i) centred.row(i) = (markers[i] - c).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix<double, 4, 3>> svd(centred);
  const auto& s = svd.singularValues();
  return s[0] > 0 ? s[2] / s[0] : 0.0;
}

bool finite_markers(const Markers& m) {
  return std::all_of(m.begin(), m.end(), [](const Eigen::Vector3d& p) { return p.allFinite(); });
}

}  // namespace

std::optional<std::string> analysis_problem(const std::vector<Markers>& targets, const AnalysisSettings& s) {
  if (targets.empty()) return std::string("no targets");
  const auto bad_limits = [](const Eq1Limits& l) {
    return !(std::isfinite(l.d1) && std::isfinite(l.d2) && std::isfinite(l.h) && l.d1 >= 0 && l.d2 > l.d1 &&
             l.h >= 0 && l.w >= 0 && l.w <= 1);
  };
  if (bad_limits(s.limits)) return std::string("limits need 0 <= d1 < d2, h >= 0 and w in [0, 1]");
  if (bad_limits(s.top_view)) return std::string("top-view limits need 0 <= d1 < d2, h >= 0 and w in [0, 1]");
  if (s.sphere.views < 1 || s.sphere.views > 1'000'000) {
    return "views must be 1 .. 1000000, got " + std::to_string(s.sphere.views);
  }
  for (size_t t = 0; t < targets.size(); ++t) {
    if (!finite_markers(targets[t])) return "target " + std::to_string(t) + " has a marker that is not finite";
    const double needed = 2 * target_radius(targets[t]);
    if (!(s.sphere.distance > needed) || !std::isfinite(s.sphere.distance)) {
      return "view distance must exceed twice the target's radius (" + number_text(needed) + " m for target " +
             std::to_string(t) + "), got " + number_text(s.sphere.distance);
    }
  }
  return std::nullopt;
}

SystemAnalysis analyse_targets(const std::vector<Markers>& targets, const std::vector<double>& marker_diameters,
                               const AnalysisSettings& s) {
  SystemAnalysis out;
  const std::vector<TargetShape> top =
      top_view_shapes(targets, std::vector<Eigen::Vector3d>(targets.size(), Eigen::Vector3d::UnitZ()));
  std::vector<TargetShape> shapes;
  out.shortest = INFINITY;
  out.longest = -INFINITY;
  for (size_t t = 0; t < targets.size(); ++t) {
    TargetAnalysis a;
    a.distances = edges_of(targets[t]);
    a.spread = distance_spread(std::vector<double>(a.distances.begin(), a.distances.end()));
    a.face_heights = face_heights(a.distances);
    a.min_face_height = *std::min_element(a.face_heights.begin(), a.face_heights.end());
    a.min_triangle_altitude = min_triangle_altitude(a.distances);
    a.volume_ratio = volume_ratio(a.distances);
    a.flatness = flatness_of(targets[t]);
    a.top_view = top[t];
    a.conditioning = pose_conditioning(targets[t], t < marker_diameters.size() ? marker_diameters[t] : 0.0, s.sphere);
    const int index = static_cast<int>(t);
    for (int e = 0; e < 6; ++e) {
      const double d = a.distances[e];
      out.shortest = std::min(out.shortest, d);
      out.longest = std::max(out.longest, d);
      if (d < s.limits.d1) out.violations.push_back({index, kEdgeNames[e], d, s.limits.d1, false});
      if (d > s.limits.d2) out.violations.push_back({index, kEdgeNames[e], d, s.limits.d2, true});
    }
    for (int k = 0; k < 4; ++k) {
      const double h = a.face_heights[k];
      if (h < s.limits.h) out.violations.push_back({index, kHeightNames[k], h, s.limits.h, false});
    }
    shapes.push_back(solid_shape(a.distances));
    out.targets.push_back(a);
  }
  out.score = eq1_score(shapes, s.limits);
  out.top_score = eq1_score(top, s.top_view);
  return out;
}

}  // namespace tetrapulse::hardware
