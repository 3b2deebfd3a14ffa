#pragma once
// Reproducible random numbers: stream `index` of `seed` is the same sequence on every
// machine, compiler and thread count (SplitMix64, Steele, Lea & Flood, OOPSLA 2014;
// no std:: distributions, whose output the standard leaves to the library).
#include <cstdint>

namespace tetrapulse::hardware {

class SeededStream {
 public:
  SeededStream(uint64_t seed, uint64_t index) : state_(mix(seed ^ mix(index + 0x9e3779b97f4a7c15ULL))) {}

  uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix(state_);
  }
  // Uniform in [0, 1), 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform integer in [0, n), n >= 1.
  int below(int n) { return static_cast<int>(uniform() * n); }

 private:
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  uint64_t state_;
};

}  // namespace tetrapulse::hardware
