#include "target_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "json_text.hpp"

namespace tetrapulse::cli {

namespace {

constexpr double kDegrees = 180.0 / M_PI;

std::string target_label(const TargetsFile& targets, int index) {
  const Target& t = targets.targets[static_cast<size_t>(index)];
  return t.name.empty() ? fmt::format("target {}", t.id) : fmt::format("target {} ({})", t.id, t.name);
}

// JSON has no infinity: an unbounded conditioning is written as null.
std::string json_number(double x) { return std::isfinite(x) ? fmt::format("{}", x) : "null"; }

template <typename Range>
std::string json_numbers(const Range& values) {
  std::string out = "[";
  for (const double v : values) out += (out.size() > 1 ? ", " : "") + json_number(v);
  return out + "]";
}

std::string json_vector(const Eigen::Vector3d& v) { return json_numbers(std::array<double, 3>{v.x(), v.y(), v.z()}); }

std::string json_limits(const hardware::Eq1Limits& l) {
  return fmt::format(R"({{"d1_m": {}, "d2_m": {}, "h_m": {}, "w": {}}})", l.d1, l.d2, l.h, l.w);
}

std::string json_score(const hardware::Eq1Score& s) {
  return fmt::format(R"({{"f_m": {}, "s_min_m": {}, "s_avg_m": {}, "violation_m": {}}})", json_number(s.f),
                     json_number(s.spread.s_min), json_number(s.spread.s_avg), json_number(s.violation));
}

std::string text_numbers(const hardware::Edges& d) {
  return fmt::format("{:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f}", d[0], d[1], d[2], d[3], d[4], d[5]);
}

std::string text_score(const hardware::Eq1Score& s, const hardware::Eq1Limits& l) {
  std::string out = fmt::format("s_min {:.6f} m, s_avg {:.6f} m, f {:.6f} m", s.spread.s_min, s.spread.s_avg, s.f);
  if (s.violation > 0) {
    out += fmt::format(" (penalised: constraints fail by {:.6f} m; w s_min + (1 - w) s_avg = {:.6f} m)", s.violation,
                       l.w * s.spread.s_min + (1 - l.w) * s.spread.s_avg);
  }
  return out;
}

}  // namespace

std::string describe_violation(const TargetsFile& targets, const hardware::Violation& v) {
  const bool distance = v.quantity[0] == 'd';
  const char* limit = distance ? (v.above ? "D2" : "D1") : "H";
  return fmt::format("{}: {} = {:.6f} m {} {} = {} m", target_label(targets, v.target), v.quantity, v.value,
                     v.above ? ">" : "<", limit, v.limit);
}

std::string format_target_check_text(const std::string& file, const TargetsFile& targets,
                                     const hardware::SystemAnalysis& a, const hardware::AnalysisSettings& s) {
  const hardware::Eq1Limits& l = s.limits;
  const hardware::Eq1Limits& top = s.top_view;
  std::string out = fmt::format("{}: {} target{}; D1 {} m, D2 {} m, H {} m, w {:.4f}\n", file, a.targets.size(),
                                a.targets.size() == 1 ? "" : "s", l.d1, l.d2, l.h, l.w);
  out += fmt::format("system: {}; distances {:.6f} .. {:.6f} m\n", text_score(a.score, l), a.shortest, a.longest);
  out += fmt::format("system top view (along each target's z; D1' {} m, D2' {} m, H' {} m): {}\n", top.d1, top.d2,
                     top.h, text_score(a.top_score, top));
  for (size_t t = 0; t < a.targets.size(); ++t) {
    const hardware::TargetAnalysis& x = a.targets[t];
    const hardware::PoseConditioning& c = x.conditioning;
    out += fmt::format("{}: distances d01 d02 d03 d12 d13 d23 = {} m; own s_min {:.6f} m\n",
                       target_label(targets, static_cast<int>(t)), text_numbers(x.distances), x.spread.s_min);
    out += fmt::format("  face heights (marker to opposite face) h0..h3 = {:.6f} {:.6f} {:.6f} {:.6f} m, min {:.6f} m;"
                       " min triangle altitude {:.6f} m\n",
                       x.face_heights[0], x.face_heights[1], x.face_heights[2], x.face_heights[3], x.min_face_height,
                       x.min_triangle_altitude);
    out += fmt::format("  degeneracy: volume {:.3f} of a regular tetrahedron's (same RMS edge), flatness "
                       "sigma3/sigma1 {:.3f}\n",
                       x.volume_ratio, x.flatness);
    out += fmt::format("  top view: projected distances {:.6f} .. {:.6f} m, min triangle altitude {:.6f} m\n",
                       *std::min_element(x.top_view.distances.begin(), x.top_view.distances.end()),
                       *std::max_element(x.top_view.distances.begin(), x.top_view.distances.end()),
                       x.top_view.face_height);
    out += fmt::format("  pose conditioning at {} m over {} views: worst kappa {:.1f} from [{:.3f}, {:.3f}, {:.3f}]"
                       " (from above: {:.1f}); closest pair median {:.2f} deg; discs overlap in {:.1f}% of views\n",
                       s.sphere.distance, s.sphere.views, c.worst_kappa, c.worst_direction.x(),
                       c.worst_direction.y(), c.worst_direction.z(), c.worst_kappa_above,
                       c.median_closest_rad * kDegrees, 100 * c.overlap_fraction);
  }
  if (a.violations.empty()) {
    out += "OK: every distance in [D1, D2] and every face height >= H\n";
  } else {
    for (const hardware::Violation& v : a.violations) out += "FAIL: " + describe_violation(targets, v) + "\n";
  }
  return out;
}

std::string format_target_check_json(const std::string& file, const TargetsFile& targets,
                                     const hardware::SystemAnalysis& a, const hardware::AnalysisSettings& s) {
  std::string out = "{\n";
  out += fmt::format("  \"file\": {},\n  \"limits\": {},\n  \"top_view_limits\": {},\n", json_string(file),
                     json_limits(s.limits), json_limits(s.top_view));
  out += fmt::format("  \"view_sphere\": {{\"distance_m\": {}, \"views\": {}}},\n", s.sphere.distance, s.sphere.views);
  out += fmt::format("  \"score\": {},\n  \"top_view_score\": {},\n", json_score(a.score), json_score(a.top_score));
  out += fmt::format("  \"shortest_m\": {},\n  \"longest_m\": {},\n  \"targets\": [\n", a.shortest, a.longest);
  for (size_t t = 0; t < a.targets.size(); ++t) {
    const hardware::TargetAnalysis& x = a.targets[t];
    const hardware::PoseConditioning& c = x.conditioning;
    const Target& file_target = targets.targets[t];
    out += fmt::format(
        "    {{\"id\": {}, \"name\": {}, \"distances_m\": {}, \"s_min_m\": {}, \"s_avg_m\": {},\n"
        "     \"face_heights_m\": {}, \"min_face_height_m\": {}, \"min_triangle_altitude_m\": {},\n"
        "     \"volume_ratio\": {}, \"flatness\": {},\n"
        "     \"top_view\": {{\"distances_m\": {}, \"min_triangle_altitude_m\": {}}},\n"
        "     \"pose_conditioning\": {{\"worst_kappa\": {}, \"worst_direction\": {}, \"worst_kappa_above\": {}, "
        "\"median_closest_deg\": {}, \"overlap_fraction\": {}}}}}{}\n",
        file_target.id, json_string(file_target.name), json_numbers(x.distances), x.spread.s_min, x.spread.s_avg,
        json_numbers(x.face_heights), x.min_face_height, x.min_triangle_altitude, x.volume_ratio, x.flatness,
        json_numbers(x.top_view.distances), x.top_view.face_height, json_number(c.worst_kappa),
        json_vector(c.worst_direction), json_number(c.worst_kappa_above), c.median_closest_rad * kDegrees,
        c.overlap_fraction, t + 1 < a.targets.size() ? "," : "");
  }
  out += "  ],\n  \"violations\": [";
  for (size_t i = 0; i < a.violations.size(); ++i) {
    const hardware::Violation& v = a.violations[i];
    out += fmt::format("{}\n    {{\"target\": {}, \"quantity\": {}, \"value_m\": {}, \"limit_m\": {}, \"above\": {}}}",
                       i ? "," : "", targets.targets[static_cast<size_t>(v.target)].id, json_string(v.quantity),
                       v.value, v.limit, v.above ? "true" : "false");
  }
  out += a.violations.empty() ? "],\n" : "\n  ],\n";
  out += fmt::format("  \"ok\": {}\n}}\n", a.violations.empty() ? "true" : "false");
  return out;
}

}  // namespace tetrapulse::cli
