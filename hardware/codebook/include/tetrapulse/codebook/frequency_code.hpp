#pragma once
// One frequency code as one camera sees it (SPEC.md §8.5).
//
// A frequency code is a square wave: `ones` 1 bits, then `length - ones` 0 bits
// (0 < ones < length), played cyclically with bit period T (SPEC.md §9). Its
// period is C = length * T. A camera with frame period P exposing
// [t0 + k P, t0 + k P + E) samples it once per frame and sees its apparent
// (aliased) frequency, in cycles per frame:
//     nu = dist(P / C, Z) = min(P mod C, C - P mod C) / C,   0 <= nu <= 1/2.
// A board clock off by up to e ppm moves nu by at most
//     drift = e 1e-6 P / C.
// Frequencies are unsigned Q32 cycles per frame (2^32 = one cycle per frame),
// exact floors of the rational values above. Times are integer nanoseconds.
// Freestanding: integer arithmetic only.
#include <cstdint>

#include "tetrapulse/protocol/code.hpp"  // SquareWave, is_square_wave

namespace tetrapulse::protocol {

// A camera's sampling: frame period P and exposure E, 0 < E <= P.
struct CameraTiming {
  int64_t frame_period_ns = 10'000'000;
  int64_t exposure_ns = 1'000'000;
};

// One cycle per frame in Q32.
constexpr uint64_t kCyclePerFrameQ32 = uint64_t{1} << 32;

// floor(a * 2^32 / b), for b > 0, b < 2^55 and a < b 2^31 (saturates otherwise).
uint64_t ratio_q32(uint64_t a, uint64_t b);

// nu of a code with period `code_period_ns` sampled every `frame_period_ns` (Q32).
uint32_t apparent_frequency_q32(int64_t frame_period_ns, int64_t code_period_ns);

// drift = ppm 1e-6 P / C (Q32), the most a clock error of `ppm` moves nu.
uint32_t frequency_drift_q32(int64_t frame_period_ns, int64_t code_period_ns, uint32_t ppm);

// How the camera sees one square wave, over every phase of the board against
// the camera (exactly, to the nanosecond of phase):
struct WaveVisibility {
  // Longest run of consecutive frames whose exposure is lit less than half of
  // its duration (the marker looks dark with on_off modulation); capped at cap + 1.
  uint32_t dark_frames = 0;
  // Swing of the lit fraction of an exposure between the best and the worst
  // phase, percent of the exposure: what a reader sees of the modulation.
  uint32_t swing_percent = 0;
};
WaveVisibility wave_visibility(const CameraTiming& camera, int64_t bit_period_ns, SquareWave wave,
                               uint32_t dark_cap);

// Nanoseconds of [start, start + duration) during which a square wave with
// period `period_ns` that is lit over [0, on_ns) of each period is lit.
// start >= 0, duration >= 0, 0 <= on_ns <= period_ns.
int64_t lit_ns(int64_t start_ns, int64_t duration_ns, int64_t period_ns, int64_t on_ns);

}  // namespace tetrapulse::protocol
