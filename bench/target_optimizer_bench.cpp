// The target-geometry optimiser (hardware/optimizer): whole optimisations as
// `tetrapulse target optimize` runs them, and the Eq. 1 evaluation at their core.
#include <benchmark/benchmark.h>

#include <vector>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/seeded_stream.hpp"
#include "tetrapulse/hardware/target_optimizer.hpp"
#include "tetrapulse/hardware/top_view.hpp"

namespace tetrapulse::hardware {
namespace {

// Args: targets, restarts, threads. The paper's D1, D2, H; w = default_weight.
void BM_OptimizeTargets(benchmark::State& state) {
  OptimizerSettings s;
  s.targets = static_cast<int>(state.range(0));
  s.restarts = static_cast<int>(state.range(1));
  s.threads = static_cast<int>(state.range(2));
  s.limits.w = default_weight(6 * s.targets);
  s.top_view = default_top_view_limits(s.limits);
  double s_min = 0;
  for (auto _ : state) {
    const auto result = optimize_targets(s);
    s_min = result ? result->score.spread.s_min : 0;
    benchmark::DoNotOptimize(s_min);
  }
  state.counters["s_min_mm"] = s_min * 1e3;
}
BENCHMARK(BM_OptimizeTargets)
    ->Args({1, 1000, 1})
    ->Args({1, 1000, 2})
    ->Args({8, 100, 2})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);

// One target's six distances against the other targets' fixed ones: the inner loop of
// the joint optimisation. Arg: number of targets in the system.
void BM_SpreadWithFixedTargets(benchmark::State& state) {
  const int targets = static_cast<int>(state.range(0));
  SeededStream random(1, 0);
  std::vector<double> fixed;
  for (int i = 0; i < 6 * (targets - 1); ++i) fixed.push_back(0.15 + 0.15 * random.uniform());
  const DistancePool pool(fixed);
  Edges moving{};
  for (double& d : moving) d = 0.15 + 0.15 * random.uniform();
  for (auto _ : state) {
    moving[0] += 1e-12;  // a new point each time, as in the simplex
    benchmark::DoNotOptimize(pool.spread_with(moving.data(), 6));
  }
}
BENCHMARK(BM_SpreadWithFixedTargets)->Arg(1)->Arg(8)->Arg(16)->Arg(64);

}  // namespace
}  // namespace tetrapulse::hardware

BENCHMARK_MAIN();
