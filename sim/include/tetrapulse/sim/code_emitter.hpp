#pragma once
// The contract's emission model (docs/rig-dataset.md) for the four markers of one
// target board: at board time b the marker plays bit
//     floor((b - epoch_ns) / bit_period_ns) mod len(code),
// a 1 at full intensity, a 0 at `low` (two_level) or dark (on_off); `constant`
// modulation or a marker without a code emits 1 always. b is the board's notion
// of rig time (BoardClock), so a free-running or unsynchronized board plays its
// bits off the rig's by its clock error. The mean over a window is exact: the
// window is cut at every bit edge.
#include <array>
#include <optional>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/sim/board_clock.hpp"
#include "tetrapulse/sim/led_emitter.hpp"

namespace tetrapulse::sim {

class CodeEmitter : public LedEmitter {
 public:
  CodeEmitter(const Timebase& timebase, const Modulation& modulation, const Target& target, BoardClock clock);

  const BoardClock& clock() const { return clock_; }

  // Relative emission of bit value `one`.
  double level(bool one) const;

 private:
  double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const override;
  // Integral of the emission of `code` over board times [x0, x1) (board ns).
  double integrate(const Code& code, double x0, double x1) const;

  Timebase timebase_;
  Modulation modulation_;
  std::array<std::optional<Code>, 4> codes_;
  BoardClock clock_;
};

}  // namespace tetrapulse::sim
