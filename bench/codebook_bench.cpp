// The codebook search on the recommended on_off specs (SPEC.md §8.4; also the
// acceptance specs: synchronized 12 bits, d 3, weights 5-7, zero runs <= 2;
// free-running 15 bits, d 3, zero runs <= 3): time to the requested count, and
// how many codes a search budget reaches (counter "codes").
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_workspace.hpp"

namespace tetrapulse::protocol {
namespace {

CodebookWorkspace& workspace() {
  static const std::unique_ptr<CodebookWorkspace> ws = std::make_unique<CodebookWorkspace>();
  return *ws;
}

// Time to `count` codes (state.range(0)); seeds vary so no single lucky path is timed.
void generate_codes(benchmark::State& state, CodebookSpec spec) {
  spec.count = static_cast<uint16_t>(state.range(0));
  std::vector<uint64_t> out(spec.count);
  size_t found = 0;
  for (auto _ : state) {
    ++spec.seed;
    const Result<size_t> n = generate(spec, out.data(), out.size(), workspace());
    found = n.ok() ? *n : 0;
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["codes"] = static_cast<double>(found);
}

// The largest set within state.range(0) iterations, seed 1 (what the CLI's --capacity reports).
void largest_set(benchmark::State& state, CodebookSpec spec) {
  spec.search_iterations = static_cast<uint32_t>(state.range(0));
  std::vector<uint64_t> out(CodebookWorkspace::kMaxCandidates);
  CodebookSearchStats stats;
  size_t found = 0;
  for (auto _ : state) {
    const Result<size_t> n = find_largest(spec, out.data(), out.size(), workspace(), &stats);
    found = n.ok() ? *n : 0;
  }
  state.counters["codes"] = static_cast<double>(found);
  state.counters["candidates"] = stats.candidates;
}

BENCHMARK_CAPTURE(generate_codes, synchronized_l12, recommended_spec(CodeTiming::kSynchronized, ZeroBit::kDark))
    ->Arg(64)->Arg(80)->Arg(96)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(generate_codes, free_running_l15, recommended_spec(CodeTiming::kFreeRunning, ZeroBit::kDark))
    ->Arg(16)->Arg(48)->Arg(58)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(largest_set, synchronized_l12, recommended_spec(CodeTiming::kSynchronized, ZeroBit::kDark))
    ->Arg(0)->Arg(2000)->Arg(20000)->Arg(200000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(largest_set, free_running_l15, recommended_spec(CodeTiming::kFreeRunning, ZeroBit::kDark))
    ->Arg(0)->Arg(2000)->Arg(20000)->Arg(200000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace tetrapulse::protocol
