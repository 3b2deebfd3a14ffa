#pragma once
// Occlusion: light `index` is hidden from the camera (something passes in front
// of it) during rig-time intervals; its mean emission over a window counts only
// the visible part:  mean = sum over visible pieces [a, b) of inner.mean(a, b) (b - a) / (t1 - t0).
// Wraps any LedEmitter, so a simulated board's code player is occluded the same way.
#include <memory>
#include <vector>

#include "tetrapulse/sim/led_emitter.hpp"
#include "tetrapulse/sim/time_intervals.hpp"

namespace tetrapulse::sim {

class OccludedEmitter : public LedEmitter {
 public:
  // hidden[i]: when light i is occluded; lights beyond hidden.size() are never occluded.
  OccludedEmitter(std::unique_ptr<LedEmitter> inner, std::vector<TimeIntervals> hidden)
      : inner_(std::move(inner)), hidden_(std::move(hidden)) {}

  const LedEmitter& inner() const { return *inner_; }

 private:
  double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const override;

  std::unique_ptr<LedEmitter> inner_;
  std::vector<TimeIntervals> hidden_;
};

}  // namespace tetrapulse::sim
