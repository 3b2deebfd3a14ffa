#pragma once
// Which code bit a target's board plays when (docs/rig-dataset.md): bit number
//   n(t) = floor((t - origin_ns) * rate / bit_period_ns),   bit index = n mod L,
// t in integer nanoseconds of rig time. Synchronized boards: origin = epoch_ns,
// rate = 1. Free-running boards: origin and rate (1 +- 200e-6) are estimated
// from what the camera saw; origin is then kept near the samples so that the
// differences stay small.
#include <cstdint>
#include <optional>

#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

struct CodeClock {
  int64_t origin_ns = 0;          // rig time at which bit 0 starts
  int64_t bit_period_ns = 1;      // nominal T, > 0
  double rate = 1.0;              // board bits per nominal bit

  static CodeClock from(const Timebase& timebase) { return CodeClock{timebase.epoch_ns, timebase.bit_period_ns, 1.0}; }

  int64_t bit_number(int64_t t_ns) const;
};

// What a code predicts for an exposure [start_ns, start_ns + exposure_ns): the
// level of the one bit it integrates, or kMixed when it spans bits of both values.
enum class ExpectedBit : int8_t { kZero = 0, kOne = 1, kMixed = 2 };
ExpectedBit expected_bit(const CodeClock& clock, const Code& code, int64_t start_ns, int64_t exposure_ns);

// Mean relative emission of a marker over [start_ns, start_ns + exposure_ns) as
// the contract defines it: 1 in a 1 bit, `low` (two_level) or 0 (on_off) in a 0
// bit, 1 always under constant modulation or without a code.
double mean_emission(const CodeClock& clock, const Modulation& modulation, const std::optional<Code>& code,
                     int64_t start_ns, int64_t exposure_ns);

}  // namespace tetrapulse
