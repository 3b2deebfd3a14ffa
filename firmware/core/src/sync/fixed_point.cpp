#include "tetrapulse/fw/sync/fixed_point.hpp"

namespace tetrapulse::fw {
namespace {

constexpr uint64_t kLow32 = 0xFFFFFFFFu;

U128 shl(U128 x, unsigned shift) {
  if (shift == 0) return x;
  if (shift >= 64) return U128{x.lo << (shift - 64), 0};
  return U128{(x.hi << shift) | (x.lo >> (64 - shift)), x.lo << shift};
}

// Long division of a 128-bit numerator by a 64-bit divisor, bit by bit (once per servo
// sample, so speed does not matter); saturates when the quotient needs more than 64 bits.
uint64_t div_u128(U128 n, uint64_t d) {
  U128 q;
  uint64_t r = 0;
  for (int i = 127; i >= 0; --i) {
    const bool carry = (r >> 63) != 0;
    const uint64_t bit = i >= 64 ? (n.hi >> (i - 64)) & 1u : (n.lo >> i) & 1u;
    r = (r << 1) | bit;
    if (carry || r >= d) {
      r -= d;
      if (i >= 64) {
        q.hi |= uint64_t{1} << (i - 64);
      } else {
        q.lo |= uint64_t{1} << i;
      }
    }
  }
  return q.hi != 0 ? UINT64_MAX : q.lo;
}

}  // namespace

U128 mul_u64(uint64_t a, uint64_t b) {
  const uint64_t a_lo = a & kLow32, a_hi = a >> 32;
  const uint64_t b_lo = b & kLow32, b_hi = b >> 32;
  const uint64_t p0 = a_lo * b_lo;
  const uint64_t p1 = a_lo * b_hi;
  const uint64_t p2 = a_hi * b_lo;
  const uint64_t p3 = a_hi * b_hi;
  const uint64_t mid = (p0 >> 32) + (p1 & kLow32) + (p2 & kLow32);
  return U128{p3 + (p1 >> 32) + (p2 >> 32) + (mid >> 32), (p0 & kLow32) | (mid << 32)};
}

uint64_t shr_saturate(U128 x, unsigned shift) {
  if (shift >= 64) return x.hi >> (shift - 64);
  if (shift == 0) return x.hi != 0 ? UINT64_MAX : x.lo;
  if ((x.hi >> shift) != 0) return UINT64_MAX;
  return (x.lo >> shift) | (x.hi << (64 - shift));
}

uint64_t shl_div(uint64_t a, unsigned shift, uint64_t d) {
  if (d == 0) return UINT64_MAX;
  return div_u128(shl(U128{0, a}, shift), d);
}

int64_t mul_shr_signed(int64_t a, uint64_t b, unsigned shift) {
  const bool negative = a < 0;
  const uint64_t magnitude = negative ? uint64_t{0} - static_cast<uint64_t>(a) : static_cast<uint64_t>(a);
  U128 p = mul_u64(magnitude, b);
  if (shift > 0) {  // round half away from zero
    const U128 half = shl(U128{0, 1}, shift - 1);
    const uint64_t lo = p.lo + half.lo;
    p.hi += half.hi + (lo < p.lo ? 1u : 0u);
    p.lo = lo;
  }
  uint64_t r = shr_saturate(p, shift);
  if (r > static_cast<uint64_t>(INT64_MAX)) r = static_cast<uint64_t>(INT64_MAX);
  const int64_t v = static_cast<int64_t>(r);
  return negative ? -v : v;
}

int64_t div_round(int64_t a, int64_t b) {
  const int64_t half = b / 2;
  if (a >= 0) return (a > INT64_MAX - half ? a / b : (a + half) / b);
  return (a < INT64_MIN + half ? a / b : -((-a + half) / b));
}

}  // namespace tetrapulse::fw
