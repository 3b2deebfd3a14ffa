#pragma once
// Per-frame timing of the whole localizer over a rendered sequence, shared by the
// pipeline benchmarks (four_targets_sequence.hpp) and the scale benchmarks
// (scale_targets_sequence.hpp): both time one frame per iteration the same way.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>

#include <opencv2/core/utility.hpp>

#include "four_targets_sequence.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace tetrapulse::bench {

// Runs frames [from, to) of `s` through `localizer`.
inline void feed(Localizer* localizer, const Sequence& s, int from, int to) {
  for (int k = from; k < to; ++k)
    benchmark::DoNotOptimize(localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns));
}

// Times one frame per iteration from frame `warm_up` on, on one thread, restarting the
// localizer (untimed, warmed up again) at the end of the sequence. Counters: poses per
// frame, and the share of frames searched whole.
inline void time_frames(benchmark::State& state, const Sequence& s, const TargetsFile& targets,
                        const LocalizerOptions& options, int warm_up) {
  cv::setNumThreads(1);
  const int frames = int(s.images.size());
  auto localizer = std::make_unique<Localizer>(s.scenario.camera, targets, options);
  feed(localizer.get(), s, 0, warm_up);
  int k = warm_up;
  int64_t poses = 0, searched = 0;
  for (auto _ : state) {
    if (k == frames) {
      state.PauseTiming();
      localizer = std::make_unique<Localizer>(s.scenario.camera, targets, options);
      feed(localizer.get(), s, 0, warm_up);
      k = warm_up;
      state.ResumeTiming();
    }
    auto out = localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
    poses += out ? int64_t(out->size()) : 0;
    searched += localizer->searched_whole_image();
    ++k;
  }
  state.counters["poses_per_frame"] = double(poses) / double(state.iterations());
  state.counters["whole_image_share"] = double(searched) / double(state.iterations());
}

// Frames [from, end) of a sequence through a localizer, in a function that is not
// inlined, so that callgrind --toggle-collect can name it.
using SequenceFrames = void (*)(Localizer*, const Sequence&, int from);

// Frames `warm_up` to the end of `s` once per iteration through `frames`, after
// `warm_up` untimed ones into a fresh localizer: the same frames every run, for
// instruction counts. Counter: per_frame_us.
inline void time_sequence(benchmark::State& state, const Sequence& s, const TargetsFile& targets,
                          const LocalizerOptions& options, int warm_up, SequenceFrames frames) {
  cv::setNumThreads(1);
  for (auto _ : state) {
    state.PauseTiming();
    Localizer localizer(s.scenario.camera, targets, options);
    feed(&localizer, s, 0, warm_up);
    state.ResumeTiming();
    frames(&localizer, s, warm_up);
  }
  state.counters["per_frame_us"] =
      benchmark::Counter(double(s.images.size() - size_t(warm_up)) * 1e-6,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace tetrapulse::bench
