#include "motion_yaml.hpp"

#include <cmath>

#include <fmt/format.h>

#include "map_reader.hpp"

namespace tetrapulse::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;

Pose read_pose(MapReader& r, const std::string& position_key) {
  const Eigen::Vector3d p = r.vec3(position_key, Range::any());
  const Eigen::Vector3d rpy = r.vec3("rpy_deg", Range::any(), Eigen::Vector3d::Zero());
  return Pose{rotation_from_rpy(rpy * kDeg), p};
}

MotionSpec read_waypoints(MapReader& r) {
  WaypointMotion m;
  m.loop = r.boolean("loop", false);
  const YAML::Node points = r.child("points");
  if (!r.ok()) return m;
  if (!points.IsSequence() || points.size() == 0) {
    r.fail("points", "expected a non-empty list of {t_s, position_m, rpy_deg}");
    return m;
  }
  for (size_t i = 0; i < points.size() && r.ok(); ++i) {
    MapReader p(r.fields(), points[i], fmt::format("{}[{}]", r.path_of("points"), i), {"t_s", "position_m", "rpy_deg"});
    Waypoint w;
    w.t_s = p.number("t_s", Range::any());
    w.pose = read_pose(p, "position_m");
    if (p.ok() && !m.points.empty() && !(w.t_s > m.points.back().t_s)) {
      p.fail("t_s", fmt::format("must be later than the previous point's {} s", m.points.back().t_s));
    }
    m.points.push_back(w);
  }
  return m;
}

MotionSpec read_smooth_random(MapReader& r, bool hover) {
  SmoothRandomMotion m;
  m.centre = read_pose(r, "position_m");
  // A hovering vehicle wanders a few centimetres and degrees; a hand-held camera is told how far.
  const std::optional<Eigen::Vector3d> amp = hover ? std::optional<Eigen::Vector3d>(Eigen::Vector3d::Constant(0.03))
                                                   : std::nullopt;
  const std::optional<Eigen::Vector3d> rot = hover ? std::optional<Eigen::Vector3d>(Eigen::Vector3d::Constant(2.0))
                                                   : std::optional<Eigen::Vector3d>(Eigen::Vector3d::Zero());
  m.amplitude_m = r.vec3("amplitude_m", Range::non_negative(), amp);
  m.rotation_amplitude_rad = r.vec3("rotation_amplitude_deg", Range::closed(0, 180), rot) * kDeg;
  m.min_period_s = r.number("min_period_s", Range::positive(), hover ? std::optional<double>(2.0) : std::nullopt);
  return m;
}

MotionSpec read_circle(MapReader& r) {
  CircleMotion m;
  m.center_m = r.vec3("center_m", Range::any());
  m.radius_m = r.number("radius_m", Range::non_negative());
  m.period_s = r.number("period_s", Range{0, INFINITY, true, false});
  m.phase_rad = r.number("phase_deg", Range::any(), 0.0) * kDeg;
  m.axis = r.vec3("axis", Range::any(), Eigen::Vector3d::UnitZ());
  if (r.ok() && !(m.axis.norm() > 1e-9)) r.fail("axis", "must not be the zero vector");
  m.orientation = rotation_from_rpy(r.vec3("rpy_deg", Range::any(), Eigen::Vector3d::Zero()) * kDeg);
  m.follow_tangent = r.boolean("follow_tangent", true);
  return m;
}

}  // namespace

MotionSpec read_motion(yaml_fields::Fields& fields, const YAML::Node& node, const std::string& path) {
  if (fields.failed()) return StaticMotion{};
  const std::string kinds = "static, waypoints, smooth_random, hover or circle";
  if (!node.IsMap() || !node["kind"].IsDefined()) {
    fields.fail(node, fmt::format("{}.kind: missing required field ({})", path, kinds));
    return StaticMotion{};
  }
  const std::string kind = fields.scalar<std::string>(node["kind"], path + ".kind", "a string");
  if (fields.failed()) return StaticMotion{};
  if (kind == "static") {
    MapReader r(fields, node, path, {"kind", "position_m", "rpy_deg"});
    return StaticMotion{read_pose(r, "position_m")};
  }
  if (kind == "waypoints") {
    MapReader r(fields, node, path, {"kind", "points", "loop"});
    return read_waypoints(r);
  }
  if (kind == "smooth_random" || kind == "hover") {
    MapReader r(fields, node, path,
                {"kind", "position_m", "rpy_deg", "amplitude_m", "rotation_amplitude_deg", "min_period_s"});
    return read_smooth_random(r, kind == "hover");
  }
  if (kind == "circle") {
    MapReader r(fields, node, path,
                {"kind", "center_m", "radius_m", "period_s", "phase_deg", "axis", "rpy_deg", "follow_tangent"});
    return read_circle(r);
  }
  fields.fail(node["kind"], fmt::format("{}.kind: '{}' is not {}", path, kind, kinds));
  return StaticMotion{};
}

}  // namespace tetrapulse::sim
