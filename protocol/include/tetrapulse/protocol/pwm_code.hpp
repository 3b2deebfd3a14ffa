#pragma once
// A raw PWM for bench checks (a scope or a phone camera on one LED), played as an
// ordinary frequency code: no new message, the board's code player does it.
//
// For a frequency F (Hz) and duty D (0 < D < 1) the code is the square wave of
// L bits with w ones on bit period T (integer ns, T >= kMinBitPeriodNs), chosen
// over L = 2..64 to minimise first the duty error |w/L - D| (w = round(D L),
// clamped to 1..L-1), then the frequency error, with T = round(1e9 / (F L)).
// Quantisation: the duty moves in steps of 1/L (1/64 when 64 T >= 10 us fits,
// i.e. up to 1562 Hz; coarser above, down to 1/2 at 50 kHz, the highest F); the
// period L T is within 0.5 L ns of 1e9 / F (under 1e-4 of it below 5 kHz, with
// L = 64 at most 32 ns). A free-running board adds its crystal's error (up to
// 200 ppm) to the frequency, not to the duty.
#include <cstdint>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

struct PwmCode {
  Code code;                  // "1..10..0"
  uint32_t bit_period_ns = 0;
  // What the board will play: 1e9 / (L T) Hz, w / L duty, in millihertz and parts per 65536.
  uint64_t frequency_millihertz = 0;
  uint32_t duty_q16 = 0;
};

// kBadValue unless 0.01 Hz <= F <= 50 kHz (frequency_millihertz 10 .. 50'000'000) and
// 0 < D < 1 (duty_q16 1 .. 65535).
Result<PwmCode> pwm_code(uint64_t frequency_millihertz, uint32_t duty_q16);

}  // namespace tetrapulse::protocol
