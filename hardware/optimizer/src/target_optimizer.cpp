#include "tetrapulse/hardware/target_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "block_ascent.hpp"
#include "grid_start.hpp"
#include "parallel_runs.hpp"
#include "tetrapulse/hardware/seeded_stream.hpp"
#include "tetrapulse/hardware/top_view.hpp"
#include "number_text.hpp"

namespace tetrapulse::hardware {

namespace {

constexpr int kMaxCandidates = 16;  // restarts taken through the top-view step
// The simplex works inside limits tightened by this (m), so that round-off in the
// embedding and placement never puts an optimum on a bound just outside it.
constexpr double kRoundOffMargin = 1e-9;
constexpr int kSwapsPerTarget = 200;  // grid_start.hpp

bool finite(double x) { return std::isfinite(x); }

std::optional<std::string> limits_problem(const Eq1Limits& l, const std::string& prefix, bool strict) {
  const char* sign = strict ? "positive" : "non-negative";
  if (!finite(l.d1) || !(strict ? l.d1 > 0 : l.d1 >= 0)) {
    return prefix + "d1 must be a " + sign + " length (m), got " + number_text(l.d1);
  }
  if (!finite(l.d2) || !(l.d2 > l.d1)) {
    return prefix + "d2 must be greater than " + prefix + "d1 (" + number_text(l.d1) + " m), got " + number_text(l.d2);
  }
  if (!finite(l.h) || !(strict ? l.h > 0 : l.h >= 0) || !(l.h < l.d2)) {
    return prefix + "h must be " + sign + " and below " + prefix + "d2 (a face height never exceeds an edge), got " +
           number_text(l.h);
  }
  if (!finite(l.w) || l.w < 0 || l.w > 1) return prefix + "w must be in [0, 1], got " + number_text(l.w);
  return std::nullopt;
}

TargetShape tetrahedron_shape(const Eigen::VectorXd& x) {
  Edges e{};
  std::copy(x.data(), x.data() + 6, e.begin());
  return solid_shape(e);
}

std::vector<Markers> embed_all(const std::vector<Edges>& edges) {
  std::vector<Markers> markers;
  for (const Edges& e : edges) markers.push_back(embed(e));
  return markers;
}

}  // namespace

std::optional<std::string> settings_problem(const OptimizerSettings& s) {
  if (s.targets < 1 || s.targets > kMaxTargets) {
    return "targets must be 1 .. " + std::to_string(kMaxTargets) + ", got " + std::to_string(s.targets);
  }
  if (auto p = limits_problem(s.limits, "", true)) return p;
  if (auto p = limits_problem(s.top_view, "top-", false)) return p;
  if (s.restarts < 1 || s.restarts > kMaxRestarts) {
    return "restarts must be 1 .. " + std::to_string(kMaxRestarts) + ", got " + std::to_string(s.restarts);
  }
  if (s.threads < 1 || s.threads > kMaxThreads) {
    return "threads must be 1 .. " + std::to_string(kMaxThreads) + ", got " + std::to_string(s.threads);
  }
  if (s.grid_levels < 2 || s.grid_levels > 100000) {
    return "grid levels must be 2 .. 100000, got " + std::to_string(s.grid_levels);
  }
  if (!finite(s.lift) || s.lift < 0 || s.lift > 10) return "lift must be 0 .. 10 m, got " + number_text(s.lift);
  return std::nullopt;
}

RestartResult optimize_restart(const OptimizerSettings& s, int index) {
  SeededStream random(s.seed, static_cast<uint64_t>(index));
  const Eq1Limits inner{s.limits.d1 + kRoundOffMargin, s.limits.d2 - kRoundOffMargin, s.limits.h + kRoundOffMargin,
                        s.limits.w};
  const GridStartSettings start{s.targets, inner, s.grid_levels, kSwapsPerTarget};
  std::vector<Eigen::VectorXd> params;
  for (const Edges& e : draw_grid_start(start, &random)) params.push_back(Eigen::Map<const Eigen::VectorXd>(e.data(), 6));
  const TargetModel model = [](int, const Eigen::VectorXd& x) { return tetrahedron_shape(x); };
  BlockAscentOptions options;
  options.simplex.step = 0.1 * (s.limits.d2 - s.limits.d1);
  options.simplex.x_tolerance = 1e-9 * s.limits.d2;
  options.simplex.f_tolerance = 1e-13 * s.limits.d2;
  RestartResult result;
  result.score = block_ascent(model, inner, options, &params);
  for (const Eigen::VectorXd& x : params) result.edges.push_back(tetrahedron_shape(x).distances);
  return result;
}

std::optional<OptimizedTargets> optimize_targets(const OptimizerSettings& s) {
  if (settings_problem(s)) return std::nullopt;
  const std::vector<RestartResult> restarts =
      run_in_parallel<RestartResult>(s.restarts, s.threads, [&](int i) { return optimize_restart(s, i); });

  // The paper's "several best solutions": every restart within kSelectTolerance of the best.
  std::vector<int> order(restarts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return restarts[a].score.f > restarts[b].score.f; });
  const double best = restarts[order[0]].score.f;
  const double margin = kSelectTolerance * std::abs(best);
  std::vector<int> candidates;
  for (int i : order) {
    if (restarts[i].score.f < best - margin || static_cast<int>(candidates.size()) == kMaxCandidates) break;
    candidates.push_back(i);
  }

  const std::vector<TopView> views = run_in_parallel<TopView>(
      static_cast<int>(candidates.size()), s.threads,
      [&](int c) { return best_top_view(embed_all(restarts[candidates[c]].edges), s.top_view); });
  size_t chosen = 0;
  for (size_t c = 1; c < candidates.size(); ++c) {
    if (views[c].score.f > views[chosen].score.f) chosen = c;  // ties keep the better shape
  }

  const RestartResult& r = restarts[candidates[chosen]];
  OptimizedTargets out;
  out.restart = candidates[chosen];
  out.candidates = static_cast<int>(candidates.size());
  const std::vector<Markers> markers = embed_all(r.edges);
  for (size_t t = 0; t < markers.size(); ++t) {
    out.targets.push_back(place_on_support(markers[t], views[chosen].up[t], s.lift));
  }
  std::vector<TargetShape> shapes;
  for (const Markers& m : out.targets) shapes.push_back(solid_shape(edges_of(m)));
  out.score = eq1_score(shapes, s.limits);
  out.top_score = eq1_score(top_view_shapes(out.targets, std::vector<Eigen::Vector3d>(out.targets.size(),
                                                                                      Eigen::Vector3d::UnitZ())),
                            s.top_view);
  return out;
}

}  // namespace tetrapulse::hardware
