// How a frame's cost grows with the number of targets (part of
// localizer_pipeline_bench; scenes in scale_targets_sequence.hpp). One thread.
//   BM_LocalizerTrackingTargets/N:  N targets tracked (ROIs only), per frame.
//   BM_LocalizerFullFrameTargets/N: every frame searched whole, with one more
//                                   target that never shows (as while one is
//                                   missing), per frame.
//   BM_LocalizerTrackingTargetsSequence/N: the tracked frames once, for callgrind.
//   BM_LocalizerAcquisitionTargets/N: a fresh localizer over its first 40
//                                   frames, which identify the N new targets
//                                   (16-bit codes: one bit per frame); per
//                                   frame, with how many were identified.
#include <benchmark/benchmark.h>

#include <memory>

#include <opencv2/core/utility.hpp>

#include "localizer_frame_timing.hpp"
#include "scale_targets_sequence.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace {

using namespace tetrapulse;
using bench::Sequence;

constexpr int kWarmUp = 40;

// One frame per iteration after kWarmUp untimed ones (localizer_frame_timing.hpp).
void time_frames(benchmark::State& state, const Sequence& s, const TargetsFile& targets,
                 const LocalizerOptions& options) {
  bench::time_frames(state, s, targets, options, kWarmUp);
}

void BM_LocalizerTrackingTargets(benchmark::State& state) {
  const Sequence& s = bench::scale_sequence(int(state.range(0)));
  time_frames(state, s, s.scenario.targets, {});
}
BENCHMARK(BM_LocalizerTrackingTargets)->Arg(1)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

// Frames kWarmUp to the sequence's end once, for instruction counts per stage:
// valgrind --tool=callgrind --toggle-collect='*scale_tracking_frames*' counts these
// calls only. Not inlined, so that callgrind can name it.
[[gnu::noinline]] void scale_tracking_frames(Localizer* localizer, const Sequence& s, int from) {
  bench::feed(localizer, s, from, int(s.images.size()));
}

void BM_LocalizerTrackingTargetsSequence(benchmark::State& state) {
  const Sequence& s = bench::scale_sequence(int(state.range(0)));
  bench::time_sequence(state, s, s.scenario.targets, {}, kWarmUp, scale_tracking_frames);
}
BENCHMARK(BM_LocalizerTrackingTargetsSequence)->Arg(4)->Arg(32)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_LocalizerFullFrameTargets(benchmark::State& state) {
  const Sequence& s = bench::scale_sequence(int(state.range(0)));
  TargetsFile targets = s.scenario.targets;
  Target absent = targets.targets[0];
  absent.id = 999;
  // The search's last four codes, which no scene uses (they use the first 4 N <= 256).
  for (size_t m = 0; m < absent.markers.size(); ++m)
    absent.markers[m].code = *parse_code(bench::scale_codes()[256 + m], nullptr);
  targets.targets.push_back(absent);
  LocalizerOptions options;
  options.full_search_interval = 1;
  time_frames(state, s, targets, options);
}
BENCHMARK(BM_LocalizerFullFrameTargets)->Arg(1)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

void BM_LocalizerAcquisitionTargets(benchmark::State& state) {
  cv::setNumThreads(1);
  const Sequence& s = bench::scale_sequence(int(state.range(0)));
  int64_t identified = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto localizer = std::make_unique<Localizer>(s.scenario.camera, s.scenario.targets);
    state.ResumeTiming();
    for (int k = 0; k < kWarmUp; ++k) {
      auto out = localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
      if (k == kWarmUp - 1 && out) identified += int64_t(out->size());
    }
  }
  state.counters["per_frame_us"] = benchmark::Counter(
      double(kWarmUp) * 1e-6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["identified"] = double(identified) / double(state.iterations());
  state.counters["per_target_per_frame_us"] =
      benchmark::Counter(double(kWarmUp) * double(state.range(0)) * 1e-6,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_LocalizerAcquisitionTargets)->Arg(1)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace
