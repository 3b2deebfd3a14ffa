#pragma once
// Seeded pseudo-random numbers that give the same sequence on every platform
// (the standard library's distributions do not), so that one scenario and seed
// always render the same bytes. Generator: xoshiro256** (Blackman & Vigna 2018),
// seeded through SplitMix64.
#include <cstdint>

namespace tetrapulse::sim {

// SplitMix64 step: a good 64-bit mix of `x`; also derives independent stream seeds.
uint64_t mix64(uint64_t x);

// Seed of an independent stream: e.g. stream_seed(seed, kNoiseStream, frame).
uint64_t stream_seed(uint64_t seed, uint64_t stream, uint64_t index = 0);

class Random {
 public:
  explicit Random(uint64_t seed);

  uint64_t next() {
    const uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t s_[4];
};

// Well-known stream identifiers (any distinct values would do; fixed so datasets stay reproducible).
enum RandomStream : uint64_t {
  kStreamSensorNoise = 1,
  kStreamFixedPattern = 2,
  kStreamBackground = 3,
  kStreamMotion = 4,
  kStreamDroppedFrames = 5,
  kStreamBrightness = 6,
};

}  // namespace tetrapulse::sim
