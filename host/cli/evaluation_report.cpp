#include "evaluation_report.hpp"

#include <cmath>

#include <fmt/format.h>

namespace tetrapulse::cli {

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string latency(const TargetEvaluation& t) {
  if (t.episodes == 0) return "-";
  return t.first_latency_frames ? fmt::format("{}/{}", *t.first_latency_frames, t.max_latency_frames) : "never";
}

std::string line(const TargetEvaluation& t, const std::string& name) {
  return fmt::format("{:<8} {:>6}  {:>7.2f} {:>7.2f} {:>7.2f} {:>8.2f}  {:>6.3f} {:>6.3f} {:>6.3f} {:>7.3f}  {:>7.2f}%  {:>9}  {:>5}\n",
                     name, t.rows, 1e3 * t.position_m.mean, 1e3 * t.position_m.median, 1e3 * t.position_m.p95,
                     1e3 * t.position_m.max, kDeg * t.orientation_rad.mean, kDeg * t.orientation_rad.median,
                     kDeg * t.orientation_rad.p95, kDeg * t.orientation_rad.max, 100 * t.coverage(), latency(t),
                     t.misidentified);
}

std::string json_stats(const ErrorStats& s, double scale) {
  return fmt::format("{{\"count\":{},\"mean\":{},\"median\":{},\"p95\":{},\"max\":{}}}", s.count, scale * s.mean,
                     scale * s.median, scale * s.p95, scale * s.max);
}

std::string json_target(const TargetEvaluation& t) {
  return fmt::format(
      "{{\"target\":{},\"rows\":{},\"position_m\":{},\"orientation_deg\":{},\"visible_frames_total\":{},\"visible_frames\":{},"
      "\"covered_frames\":{},\"coverage\":{},\"episodes\":{},\"first_latency_frames\":{},\"max_latency_frames\":{},"
      "\"misidentified\":{}}}",
      t.target < 0 ? std::string("null") : std::to_string(t.target), t.rows, json_stats(t.position_m, 1),
      json_stats(t.orientation_rad, kDeg), t.visible_frames_total, t.visible_frames, t.covered_frames, t.coverage(), t.episodes,
      t.first_latency_frames ? std::to_string(*t.first_latency_frames) : std::string("null"), t.max_latency_frames,
      t.misidentified);
}

}  // namespace

std::string evaluation_table(const Evaluation& e, const std::string& title) {
  std::string out = title.empty() ? std::string() : title + "\n";
  out += fmt::format("{:<8} {:>6}  {:^33}  {:^29}  {:>8}  {:>9}  {:>5}\n", "target", "rows",
                     "position error (mm)", "orientation error (deg)", "coverage", "latency", "misid");
  out += fmt::format("{:<8} {:>6}  {:>7} {:>7} {:>7} {:>8}  {:>6} {:>6} {:>6} {:>7}  {:>8}  {:>9}  {:>5}\n", "", "",
                     "mean", "median", "p95", "max", "mean", "median", "p95", "max", "", "first/max", "");
  for (const TargetEvaluation& t : e.targets) out += line(t, std::to_string(t.target));
  if (e.targets.size() > 1) out += line(e.overall, "all");
  return out;
}

std::string evaluation_markdown_header() {
  return "| scenario | poses | position error mean / p95 / max (mm) | orientation error mean / p95 / max (deg) | "
         "coverage | identification latency (frames) | misidentified |\n"
         "|---|---:|---|---|---:|---:|---:|\n";
}

std::string evaluation_markdown_row(const Evaluation& e, const std::string& title) {
  const TargetEvaluation& t = e.overall;
  return fmt::format("| {} | {} | {:.2f} / {:.2f} / {:.2f} | {:.3f} / {:.3f} / {:.3f} | {:.2f} % | {} | {} |\n", title,
                     t.rows, 1e3 * t.position_m.mean, 1e3 * t.position_m.p95, 1e3 * t.position_m.max,
                     kDeg * t.orientation_rad.mean, kDeg * t.orientation_rad.p95, kDeg * t.orientation_rad.max,
                     100 * t.coverage(), t.max_latency_frames, t.misidentified);
}

std::string evaluation_json(const Evaluation& e) {
  std::string out = "{\"targets\":[";
  for (size_t i = 0; i < e.targets.size(); ++i) out += (i ? "," : "") + json_target(e.targets[i]);
  out += "],\"overall\":" + json_target(e.overall) + fmt::format(",\"episode_gap_frames\":{}}}\n", e.episode_gap_frames);
  return out;
}

}  // namespace tetrapulse::cli
