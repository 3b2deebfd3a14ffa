#pragma once
// 64 x 64 -> 128-bit integer helpers for the clock arithmetic. Cortex-M4 has no 128-bit
// type (and the firmware uses no double on hot paths), so products of tick counts and
// fixed-point rates go through these.
#include <cstdint>

namespace tetrapulse::fw {

struct U128 {
  uint64_t hi = 0;
  uint64_t lo = 0;
};

// a * b, exact.
U128 mul_u64(uint64_t a, uint64_t b);
// x >> shift (shift < 128), saturated to UINT64_MAX when it does not fit.
uint64_t shr_saturate(U128 x, unsigned shift);
// (a << shift) / d, saturated to UINT64_MAX; d > 0, shift < 64.
uint64_t shl_div(uint64_t a, unsigned shift, uint64_t d);
// round(a * b / 2^shift) with a signed: the sign follows a; saturates to +-INT64_MAX.
int64_t mul_shr_signed(int64_t a, uint64_t b, unsigned shift);
// round(a / b), b > 0, rounding halves away from zero.
int64_t div_round(int64_t a, int64_t b);
// clamp to [lo, hi]
constexpr int64_t clamp64(int64_t v, int64_t lo, int64_t hi) { return v < lo ? lo : (v > hi ? hi : v); }

}  // namespace tetrapulse::fw
