#include "tetrapulse/sim/code_emitter.hpp"

#include <cmath>

#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::sim {

CodeEmitter::CodeEmitter(const Timebase& timebase, const Modulation& modulation, const Target& target,
                         BoardClock clock)
    : timebase_(timebase), modulation_(modulation), clock_(std::move(clock)) {
  for (size_t m = 0; m < codes_.size(); ++m) codes_[m] = target.markers[m].code;
}

double CodeEmitter::level(bool one) const {
  if (one || modulation_.kind == ModulationKind::kConstant) return 1.0;
  return modulation_.kind == ModulationKind::kTwoLevel ? modulation_.low : 0.0;
}

double CodeEmitter::integrate(const Code& code, double x0, double x1) const {
  const double epoch = static_cast<double>(timebase_.epoch_ns);
  const double T = static_cast<double>(timebase_.bit_period_ns);
  const int64_t L = code.length;
  int64_t n = static_cast<int64_t>(std::floor((x0 - epoch) / T));
  double total = 0;
  double x = x0;
  while (x < x1) {
    const double edge = epoch + static_cast<double>(n + 1) * T;
    // Whole code cycles at once, so that a long window costs no more than a short one.
    if (edge < x1 && x1 - edge > static_cast<double>(L) * T) {
      total += (edge - x) * level(code.bit(static_cast<uint32_t>(protocol::floor_mod(n, L))));
      double cycle_sum = 0;
      for (uint32_t i = 0; i < code.length; ++i) cycle_sum += level(code.bit(i)) * T;
      const auto cycles = static_cast<int64_t>(std::floor((x1 - edge) / (static_cast<double>(L) * T)));
      total += static_cast<double>(cycles) * cycle_sum;
      x = edge + static_cast<double>(cycles * L) * T;
      n += 1 + cycles * L;
      continue;
    }
    const double end = edge < x1 ? edge : x1;
    total += (end - x) * level(code.bit(static_cast<uint32_t>(protocol::floor_mod(n, L))));
    x = end;
    ++n;
  }
  return total;
}

double CodeEmitter::do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const {
  if (index < 0 || index >= static_cast<int>(codes_.size()) || t1_ns <= t0_ns) return 0.0;
  const std::optional<Code>& code = codes_[static_cast<size_t>(index)];
  if (!code || code->length == 0 || modulation_.kind == ModulationKind::kConstant) return 1.0;
  double total = 0;  // rig ns x emission
  clock_.pieces(t0_ns, t1_ns, [&](int64_t a, int64_t b, double board_a, double rate) {
    const double board_b = board_a + rate * static_cast<double>(b - a);
    total += integrate(*code, board_a, board_b) / rate;  // d(rig time) = d(board time) / rate
  });
  return total / static_cast<double>(t1_ns - t0_ns);
}

}  // namespace tetrapulse::sim
