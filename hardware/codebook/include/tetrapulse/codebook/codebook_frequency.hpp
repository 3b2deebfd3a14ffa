#pragma once
// The frequency family of the codebook (SPEC.md §8.5): square waves of
// different lengths on one bit period, whose apparent frequencies at one camera
// stay apart (frequency_code.hpp defines nu, drift, dark frames and swing).
//
// With m = 1/W (W: identification window in frames), a square wave c on bit
// period T is admissible for a spec when
//   nu(c) - drift(c) >= m              at least one apparent cycle per window (never a constant),
//   1/2 - nu(c) - drift(c) >= m / 2    its mirror 1 - nu stays m away (never Nyquist, whose
//                                      amplitude depends on the phase),
//   dark_frames(c) <= max_dark_frames  (on_off: the tracker keeps it), swing(c) >= min_swing_percent,
// and a set is separable with margin M (>= m) when every pair a != b has
//   |nu(a) - nu(b)| >= M + drift(a) + drift(b):
// whatever the clock errors, two apparent frequencies stay M apart, which a
// reader resolves over 1/M frames. Dropped frames do not move apparent
// frequencies (they remove samples, not shift them), so the margin holds with
// drops; a reader needs the span, not every frame. Sorted by nu, neighbours are
// enough: gaps add up. Distinct nu means distinct signals, so no code equals
// another under any cyclic shift.
//
// Choice: for each length L = 2..64 the admissible wave with the fewest ones
// from ceil(L/2) up (duty nearest 50 %: the strongest fundamental). Among them
// the largest separable set by dynamic programming over nu (exact for this
// neighbour form). For `count` codes, the margin M is raised (binary search)
// until no `count` codes are separable any more, and the last set kept: codes
// as far apart as the camera allows, so readers decide soonest. With bit period
// 0 in the spec, T = round(P / k), k = 1..kMaxBitDivisor (T >= 10 us), is tried
// too and the one giving the largest M (capacity: the most codes) is kept,
// smallest k on ties.
// Freestanding, integer arithmetic only: the same spec gives the same codes everywhere.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/codebook/frequency_code.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

constexpr uint32_t kMaxFrequencyCodes = 63;  // one per length 2..64
constexpr uint32_t kMaxBitDivisor = 64;      // bit periods tried: P / 1 .. P / 64
constexpr uint8_t kNoDarkLimit = 0xFF;       // two_level: a 0 bit is dim, never dark

struct FrequencySpec {
  CameraTiming camera;
  int64_t bit_period_ns = 0;        // T; 0: choose from P / k
  uint16_t window_frames = 24;      // W >= 4: apparent frequencies kept 1/W apart
  uint32_t clock_ppm = 200;         // board clock error bound (docs/rig-dataset.md)
  uint8_t max_dark_frames = 3;      // kNoDarkLimit with two_level
  uint8_t min_swing_percent = 50;   // 1..100
  uint16_t count = 8;               // codes wanted
};

struct FrequencyCode {
  SquareWave wave;
  uint64_t word = 0;            // square_wave_word(wave)
  uint32_t apparent_q32 = 0;    // nu
  uint32_t drift_q32 = 0;       // at spec.clock_ppm
  WaveVisibility visibility;
};

struct FrequencyCodebook {
  int64_t bit_period_ns = 0;    // T of the codes
  uint32_t capacity = 0;        // the most codes this camera separates at margin 1/W (any T tried)
  int64_t capacity_bit_period_ns = 0;  // the T that separates `capacity`
  uint32_t margin_q32 = 0;      // M: least |nu(a) - nu(b)| - drift(a) - drift(b) of the set
  uint32_t count = 0;           // spec.count, or 0 when capacity < spec.count (refused)
  FrequencyCode codes[kMaxFrequencyCodes];  // by length, then ones
};

// Why a spec cannot be used (static text), or nullptr when it can.
const char* check_frequency_spec(const FrequencySpec& spec);

// Fills *out as above. kBadValue when check_frequency_spec fails. A request the
// camera cannot meet is not an error here: count is then 0 and capacity says
// the most it can.
Status choose_frequency_codes(const FrequencySpec& spec, FrequencyCodebook* out);

// What check_frequency_codes found wrong; `code`/`other` index the input.
enum class FrequencyFault : uint8_t {
  kNone = 0,
  kBadSpec,          // check_frequency_spec fails, or spec.bit_period_ns is 0
  kNotSquareWave,    // not one run of 1s and one of 0s
  kNearConstant,     // nu - drift < m
  kNearNyquist,      // 1/2 - nu - drift < m/2
  kTooDark,          // dark_frames > max_dark_frames
  kTooFaint,         // swing < min_swing_percent
  kTooClose,         // |nu(a) - nu(b)| < m + drift(a) + drift(b)
};
const char* frequency_fault_name(FrequencyFault fault);

struct FrequencyReport {
  FrequencyFault fault = FrequencyFault::kNone;
  uint16_t code = 0;
  uint16_t other = 0;
  bool ok() const { return fault == FrequencyFault::kNone; }
};

// Every code admissible and every pair separable at margin 1/W, on spec.bit_period_ns.
// Codes are words (bit i = character i) of the given lengths.
FrequencyReport check_frequency_codes(const FrequencySpec& spec, const uint64_t* words, const uint8_t* lengths,
                                      size_t n);

// Binary codes beside frequency codes in one rig (one time base, bit period T). A binary
// word of least period p bits repeats every p T, so the camera sees it at the apparent
// frequency nu(p T) of a square wave of p bits. It stays apart from frequency code c when
//   |nu(p T) - nu(c)| >= m + drift(p T) + drift(c),
// the rule between two frequency codes: a reader that separates frequency codes by their
// apparent frequency never takes the binary code for one (a word such as "110110" is the
// square wave "110" to the camera and fails here). Harmonics are not compared.
// kTooClose: `code` indexes the binary words, `other` the frequency words; kBadSpec as
// check_frequency_codes. Codes are words (bit i = character i) of the given lengths.
FrequencyReport check_binary_beside_frequency(const FrequencySpec& spec, const uint64_t* binary_words,
                                              const uint8_t* binary_lengths, size_t n_binary,
                                              const uint64_t* frequency_words, const uint8_t* frequency_lengths,
                                              size_t n_frequency);

}  // namespace tetrapulse::protocol
