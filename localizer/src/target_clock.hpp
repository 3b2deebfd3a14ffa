#pragma once
// Internal to Localizer: the clock of one identified target's board.
//
// Synchronized boards play on the time base: the identification's clock stays.
// Free-running boards: the identification fixes the clock's origin to within a
// fraction of a bit; while the target is tracked, the origin is re-fitted (with
// rate 1) once per code length, to the one of 2 kSteps + 1 origins within half a
// bit of the current one, T / (2 kSteps) apart, whose codes explain the tracks
// best (the middle of the best run). The origin's drift over time is the board's
// rate error: rate = 1 - slope (ns per s) 1e-9, a least-squares line through the
// re-fitted origins once they span 2 s, clamped to the contract's 200 ppm.
// Times in integer nanoseconds of rig time.
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "tetrapulse/localizer/code_clock.hpp"

namespace tetrapulse::localizer_internal {

class TargetClock {
 public:
  // The clock the identification found, at mid-exposure `mid_ns`.
  void start(const CodeClock& identified, int64_t mid_ns);
  // The target was forgotten: no drift history, rate 1.
  void forget();

  // The clock codes are checked with: the latest fitted origin, rate 1.
  CodeClock fitted() const { return CodeClock{clock_.origin_ns, clock_.bit_period_ns, 1.0}; }
  // The clock with the estimated rate, same bit at the last check:
  // (tau - o) = (tau - o') rate.
  CodeClock estimated() const;

  // Re-fits the origin when `code_length` bits have passed since the last fit.
  // cost(clock) says how badly the tracks' bits fit a candidate clock (rate 1).
  void refit(int64_t mid_ns, uint32_t code_length, const std::function<double(const CodeClock&)>& cost);

 private:
  CodeClock clock_;
  int64_t checked_ns_ = 0;     // mid-exposure of the last fit
  int64_t identified_ns_ = 0;  // mid-exposure of the identification
  int64_t identified_origin_ns_ = 0;  // the origin it found
  std::vector<std::pair<double, double>> origin_drift_;  // (s since identification, origin - its first, ns)
  double rate_ = 1.0;
};

}  // namespace tetrapulse::localizer_internal
