#include "block_ascent.hpp"

namespace tetrapulse::hardware {

namespace {

std::vector<TargetShape> shapes_of(const TargetModel& model, const std::vector<Eigen::VectorXd>& params) {
  std::vector<TargetShape> shapes;
  shapes.reserve(params.size());
  for (size_t b = 0; b < params.size(); ++b) shapes.push_back(model(static_cast<int>(b), params[b]));
  return shapes;
}

}  // namespace

Eq1Score block_ascent(const TargetModel& model, const Eq1Limits& limits, const BlockAscentOptions& options,
                      std::vector<Eigen::VectorXd>* params, const SweepStart& sweep_start) {
  const int n = static_cast<int>(params->size());
  std::vector<TargetShape> shapes = shapes_of(model, *params);
  double f = eq1_score(shapes, limits).f;
  for (int sweep = 0; sweep < options.max_sweeps; ++sweep) {
    const double f_before = f;
    for (int b = 0; b < n; ++b) {
      std::vector<double> others;
      double others_violation = 0;
      for (int o = 0; o < n; ++o) {
        if (o == b) continue;
        others.insert(others.end(), shapes[o].distances.begin(), shapes[o].distances.end());
        others_violation += shape_violation(shapes[o], limits);
      }
      const DistancePool pool(std::move(others));
      const Objective objective = [&](const Eigen::VectorXd& x) {
        const TargetShape s = model(b, x);
        const double violation = others_violation + shape_violation(s, limits);
        return eq1_value(pool.spread_with(s.distances.data(), 6), violation, limits);
      };
      Eigen::VectorXd start = (*params)[b];
      if (sweep_start) {
        const Eigen::VectorXd proposed = sweep_start(b, start, objective);
        if (objective(proposed) > objective(start)) start = proposed;
      }
      const NelderMeadResult r = nelder_mead_maximize(objective, start, options.simplex);
      if (r.f > f) {
        (*params)[b] = r.x;
        shapes[b] = model(b, r.x);
        f = r.f;
      }
    }
    if (n == 1 || f - f_before <= options.tolerance) break;
  }
  return eq1_score(shapes, limits);
}

}  // namespace tetrapulse::hardware
