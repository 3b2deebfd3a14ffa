#include "tetrapulse/protocol/pwm_code.hpp"

#include "tetrapulse/protocol/code.hpp"  // SquareWave, square_wave_word

namespace tetrapulse::protocol {

Result<PwmCode> pwm_code(uint64_t frequency_millihertz, uint32_t duty_q16) {
  if (frequency_millihertz < 10 || frequency_millihertz > 50'000'000 || duty_q16 == 0 || duty_q16 >= 65536) return Error::kBadValue;
  constexpr uint64_t kNsMillihertz = 1'000'000'000'000ull;  // 1e9 ns/s x 1000 mHz/Hz
  PwmCode best;
  uint64_t best_duty_error = ~uint64_t{0};  // |w 65536 - D_q16 L| of the best, over best_length
  uint32_t best_length = 1;
  uint64_t best_period_error = ~uint64_t{0};
  for (uint32_t L = 2; L <= kMaxCodeLength; ++L) {
    const uint64_t T = (kNsMillihertz + frequency_millihertz * L / 2) / (frequency_millihertz * L);  // round(1e9 / (F L))
    if (T < kMinBitPeriodNs || T > 0xFFFFFFFFull) continue;
    uint32_t w = static_cast<uint32_t>((uint64_t{duty_q16} * L + 32768) >> 16);
    w = w < 1 ? 1 : (w > L - 1 ? L - 1 : w);
    // Duty error |w/L - D| as |w 65536 - D_q16 L| / (65536 L), compared across L by
    // cross-multiplying; period error in ns x millihertz. Exact integers.
    const uint64_t target = uint64_t{duty_q16} * L;
    const uint64_t got = uint64_t{w} << 16;
    const uint64_t duty_error = got > target ? got - target : target - got;
    const uint64_t period = T * L * frequency_millihertz;
    const uint64_t period_error = period > kNsMillihertz ? period - kNsMillihertz : kNsMillihertz - period;
    const uint64_t ours = duty_error * best_length;
    const uint64_t theirs = best_duty_error == ~uint64_t{0} ? ~uint64_t{0} : best_duty_error * L;
    if (ours < theirs || (ours == theirs && period_error < best_period_error)) {
      best_duty_error = duty_error;
      best_length = L;
      best_period_error = period_error;
      best.code = Code{static_cast<uint8_t>(L), square_wave_word(SquareWave{static_cast<uint8_t>(L), static_cast<uint8_t>(w)})};
      best.bit_period_ns = static_cast<uint32_t>(T);
      best.frequency_millihertz = (kNsMillihertz + T * L / 2) / (T * L);
      best.duty_q16 = static_cast<uint32_t>((uint64_t{w} << 16) / L);
    }
  }
  if (best.code.length == 0) return Error::kBadValue;
  return best;
}

}  // namespace tetrapulse::protocol
