#pragma once
// The codebook search's only source of randomness, so that a seed gives the same
// codes on every platform (SPEC.md §8). Integer arithmetic only.
#include <cstdint>

namespace tetrapulse::protocol {

// SplitMix64 (Steele, Lea & Flood, OOPSLA 2014), with the constants of Vigna's
// reference code:  state += 0x9E3779B97F4A7C15;  z = state;
// z = (z ^ z>>30) * 0xBF58476D1CE4E5B9;  z = (z ^ z>>27) * 0x94D049BB133111EB;
// return z ^ z>>31.  Seed 0 gives 0xE220A8397B1DCDAF first.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, n), n >= 1: draws r = next() until r >= (2^64 - n) mod n,
  // then returns r mod n (no modulo bias; usually one draw).
  uint64_t below(uint64_t n) {
    const uint64_t threshold = (0 - n) % n;
    for (;;) {
      const uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }

  // Fisher–Yates: for i = n-1 down to 1, swap a[i] with a[below(i + 1)].
  template <typename T>
  void shuffle(T* a, uint32_t n) {
    for (uint32_t i = n; i > 1; --i) {
      const uint32_t j = static_cast<uint32_t>(below(i));
      const T t = a[i - 1];
      a[i - 1] = a[j];
      a[j] = t;
    }
  }

 private:
  uint64_t state_;
};

}  // namespace tetrapulse::protocol
