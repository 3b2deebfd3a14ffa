#include "tetrapulse/codebook/codebook_frequency.hpp"

#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr uint64_t kHalfCycle = kCyclePerFrameQ32 / 2;
constexpr uint32_t kDarkReportCap = 16;  // dark runs are measured up to this many frames

uint64_t window_margin(const FrequencySpec& spec) { return kCyclePerFrameQ32 / spec.window_frames; }

bool dark_ok(const FrequencySpec& spec, const WaveVisibility& v) {
  return spec.max_dark_frames == kNoDarkLimit || v.dark_frames <= spec.max_dark_frames;
}

FrequencyFault apparent_fault(const FrequencySpec& spec, const FrequencyCode& c) {
  const uint64_t m = window_margin(spec);
  if (uint64_t{c.apparent_q32} < m + c.drift_q32) return FrequencyFault::kNearConstant;
  if (uint64_t{c.apparent_q32} + c.drift_q32 + m / 2 > kHalfCycle) return FrequencyFault::kNearNyquist;
  return FrequencyFault::kNone;
}

// nu and drift of any signal repeating every `period_ns` (a square wave's, or a binary word's).
FrequencyCode apparent_of_period(const FrequencySpec& spec, int64_t period_ns) {
  FrequencyCode c;
  c.apparent_q32 = apparent_frequency_q32(spec.camera.frame_period_ns, period_ns);
  c.drift_q32 = frequency_drift_q32(spec.camera.frame_period_ns, period_ns, spec.clock_ppm);
  return c;
}

FrequencyCode measure(const FrequencySpec& spec, int64_t bit_period_ns, SquareWave wave, bool visibility) {
  FrequencyCode c;
  c.wave = wave;
  c.word = square_wave_word(wave);
  const FrequencyCode seen = apparent_of_period(spec, static_cast<int64_t>(wave.length) * bit_period_ns);
  c.apparent_q32 = seen.apparent_q32;
  c.drift_q32 = seen.drift_q32;
  if (visibility) c.visibility = wave_visibility(spec.camera, bit_period_ns, wave, kDarkReportCap);
  return c;
}

// |nu(a) - nu(b)| - drift(a) - drift(b), or 0 when that is negative.
uint64_t pair_margin(const FrequencyCode& a, const FrequencyCode& b) {
  const uint64_t gap = a.apparent_q32 > b.apparent_q32 ? a.apparent_q32 - b.apparent_q32 : b.apparent_q32 - a.apparent_q32;
  const uint64_t drifts = uint64_t{a.drift_q32} + b.drift_q32;
  return gap > drifts ? gap - drifts : 0;
}

// The admissible waves on one bit period, one per length, sorted by nu.
struct Candidates {
  FrequencyCode code[kMaxFrequencyCodes];
  uint32_t n = 0;
};

void find_candidates(const FrequencySpec& spec, int64_t bit_period_ns, Candidates* out) {
  out->n = 0;
  for (uint32_t length = 2; length <= kMaxCodeLength; ++length) {
    const FrequencyCode probe = measure(spec, bit_period_ns, SquareWave{static_cast<uint8_t>(length), 1}, false);
    if (apparent_fault(spec, probe) != FrequencyFault::kNone) continue;
    for (uint32_t ones = (length + 1) / 2; ones < length; ++ones) {
      const FrequencyCode c =
          measure(spec, bit_period_ns, SquareWave{static_cast<uint8_t>(length), static_cast<uint8_t>(ones)}, true);
      if (!dark_ok(spec, c.visibility) || c.visibility.swing_percent < spec.min_swing_percent) continue;
      uint32_t at = out->n++;  // insertion by nu
      while (at > 0 && out->code[at - 1].apparent_q32 > c.apparent_q32) {
        out->code[at] = out->code[at - 1];
        --at;
      }
      out->code[at] = c;
      break;
    }
  }
}

// The largest set separable at margin M: a longest chain in nu order whose
// neighbours are M apart. Writes its indices (ascending) to chosen; returns its size.
uint32_t longest_chain(const Candidates& c, uint64_t M, uint32_t* chosen) {
  uint32_t size[kMaxFrequencyCodes];
  int32_t prev[kMaxFrequencyCodes];
  uint32_t best = 0;
  int32_t end = -1;
  for (uint32_t j = 0; j < c.n; ++j) {
    size[j] = 1;
    prev[j] = -1;
    for (uint32_t i = 0; i < j; ++i) {
      if (size[i] + 1 > size[j] && pair_margin(c.code[i], c.code[j]) >= M) {
        size[j] = size[i] + 1;
        prev[j] = static_cast<int32_t>(i);
      }
    }
    if (size[j] > best) {
      best = size[j];
      end = static_cast<int32_t>(j);
    }
  }
  for (int32_t k = static_cast<int32_t>(best) - 1; end >= 0; --k, end = prev[end]) {
    chosen[k] = static_cast<uint32_t>(end);
  }
  return best;
}

// The largest M at which `count` codes are separable (>= m, which must be feasible).
uint64_t widest_margin(const Candidates& c, uint64_t m, uint32_t count) {
  uint32_t chosen[kMaxFrequencyCodes];
  uint64_t lo = m;
  uint64_t hi = kHalfCycle + 1;
  while (hi - lo > 1) {
    const uint64_t mid = lo + (hi - lo) / 2;
    if (longest_chain(c, mid, chosen) >= count) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

bool before(const FrequencyCode& a, const FrequencyCode& b) {
  return a.wave.length != b.wave.length ? a.wave.length < b.wave.length : a.wave.ones < b.wave.ones;
}

// A spec and codes a check can use: any count, a bit period given, arrays present.
bool frequency_check_spec_ok(const FrequencySpec& spec, size_t n, const uint64_t* words, const uint8_t* lengths) {
  FrequencySpec s = spec;
  s.count = 1;  // the count of a spec is what generation wants; a check takes any n
  return check_frequency_spec(s) == nullptr && spec.bit_period_ns != 0 && n <= 0xFFFF &&
         (n == 0 || (words != nullptr && lengths != nullptr));
}

}  // namespace

const char* check_frequency_spec(const FrequencySpec& spec) {
  const CameraTiming& cam = spec.camera;
  if (cam.frame_period_ns <= 0 || cam.frame_period_ns > 10'000'000'000) return "frame period must be 1 ns .. 10 s";
  if (cam.exposure_ns <= 0 || cam.exposure_ns > cam.frame_period_ns) return "exposure must be 1 ns .. the frame period";
  if (spec.bit_period_ns != 0 && (spec.bit_period_ns < kMinBitPeriodNs || spec.bit_period_ns > 0xFFFFFFFFll)) {
    return "bit period must be 0 (choose) or 10 us .. 4.29 s";
  }
  if (spec.window_frames < 4 || spec.window_frames > 4096) return "window must be 4 .. 4096 frames";
  if (spec.clock_ppm > 10'000) return "clock error must be at most 10000 ppm";
  if (spec.min_swing_percent < 1 || spec.min_swing_percent > 100) return "swing must be 1 .. 100 %";
  if (spec.count < 1 || spec.count > kMaxFrequencyCodes) return "count must be 1 .. 63";
  return nullptr;
}

Status choose_frequency_codes(const FrequencySpec& spec, FrequencyCodebook* out) {
  if (check_frequency_spec(spec) != nullptr || out == nullptr) return Error::kBadValue;
  *out = FrequencyCodebook{};
  const uint64_t m = window_margin(spec);
  const int64_t P = spec.camera.frame_period_ns;
  Candidates c;
  Candidates kept;
  uint64_t kept_margin = 0;
  uint32_t chosen[kMaxFrequencyCodes];
  const uint32_t divisors = spec.bit_period_ns != 0 ? 1 : kMaxBitDivisor;
  for (uint32_t k = 1; k <= divisors; ++k) {
    const int64_t T = spec.bit_period_ns != 0 ? spec.bit_period_ns : (P + k / 2) / k;
    if (T < kMinBitPeriodNs) break;
    find_candidates(spec, T, &c);
    const uint32_t capacity = longest_chain(c, m, chosen);
    if (capacity > out->capacity) {
      out->capacity = capacity;
      out->capacity_bit_period_ns = T;
    }
    if (capacity < spec.count) continue;
    const uint64_t M = widest_margin(c, m, spec.count);
    if (M > kept_margin) {
      kept_margin = M;
      kept = c;
      out->bit_period_ns = T;
    }
  }
  if (kept_margin == 0) return Status();  // refused: capacity < count
  // The chain at the widest margin; beyond `count`, drop the slowest (lowest nu).
  const uint32_t size = longest_chain(kept, kept_margin, chosen);
  out->count = spec.count;
  out->margin_q32 = 0xFFFFFFFFu;
  for (uint32_t i = 0; i < spec.count; ++i) {
    out->codes[i] = kept.code[chosen[size - spec.count + i]];
    if (i > 0) {
      const uint64_t pm = pair_margin(out->codes[i - 1], out->codes[i]);
      out->margin_q32 = pm < out->margin_q32 ? static_cast<uint32_t>(pm) : out->margin_q32;
    }
  }
  if (spec.count == 1) out->margin_q32 = static_cast<uint32_t>(kHalfCycle);
  for (uint32_t i = 1; i < out->count; ++i) {  // by length, then ones
    const FrequencyCode x = out->codes[i];
    uint32_t at = i;
    for (; at > 0 && before(x, out->codes[at - 1]); --at) out->codes[at] = out->codes[at - 1];
    out->codes[at] = x;
  }
  return Status();
}

const char* frequency_fault_name(FrequencyFault fault) {
  switch (fault) {
    case FrequencyFault::kNone: return "none";
    case FrequencyFault::kBadSpec: return "bad_spec";
    case FrequencyFault::kNotSquareWave: return "not_square_wave";
    case FrequencyFault::kNearConstant: return "near_constant";
    case FrequencyFault::kNearNyquist: return "near_nyquist";
    case FrequencyFault::kTooDark: return "too_dark";
    case FrequencyFault::kTooFaint: return "too_faint";
    case FrequencyFault::kTooClose: return "too_close";
  }
  return "unknown";
}

FrequencyReport check_frequency_codes(const FrequencySpec& spec, const uint64_t* words, const uint8_t* lengths,
                                      size_t n) {
  FrequencyReport r;
  if (!frequency_check_spec_ok(spec, n, words, lengths)) {
    r.fault = FrequencyFault::kBadSpec;
    return r;
  }
  auto code_of = [&](size_t i, FrequencyCode* c) {
    SquareWave wave;
    if (!is_square_wave(Code{lengths[i], words[i]}, &wave)) return false;
    *c = measure(spec, spec.bit_period_ns, wave, true);
    return true;
  };
  for (size_t i = 0; i < n; ++i) {
    r.code = static_cast<uint16_t>(i);
    FrequencyCode c;
    if (!code_of(i, &c)) r.fault = FrequencyFault::kNotSquareWave;
    if (r.ok()) r.fault = apparent_fault(spec, c);
    if (r.ok() && !dark_ok(spec, c.visibility)) r.fault = FrequencyFault::kTooDark;
    if (r.ok() && c.visibility.swing_percent < spec.min_swing_percent) r.fault = FrequencyFault::kTooFaint;
    if (!r.ok()) return r;
  }
  const uint64_t m = window_margin(spec);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      SquareWave wa;
      SquareWave wb;
      is_square_wave(Code{lengths[i], words[i]}, &wa);
      is_square_wave(Code{lengths[j], words[j]}, &wb);
      const FrequencyCode a = measure(spec, spec.bit_period_ns, wa, false);
      const FrequencyCode b = measure(spec, spec.bit_period_ns, wb, false);
      if (pair_margin(a, b) < m) return FrequencyReport{FrequencyFault::kTooClose, static_cast<uint16_t>(i),
                                                        static_cast<uint16_t>(j)};
    }
  }
  return FrequencyReport{};
}

FrequencyReport check_binary_beside_frequency(const FrequencySpec& spec, const uint64_t* binary_words,
                                              const uint8_t* binary_lengths, size_t n_binary,
                                              const uint64_t* frequency_words, const uint8_t* frequency_lengths,
                                              size_t n_frequency) {
  if (!frequency_check_spec_ok(spec, n_binary, binary_words, binary_lengths) ||
      !frequency_check_spec_ok(spec, n_frequency, frequency_words, frequency_lengths)) {
    return FrequencyReport{FrequencyFault::kBadSpec, 0, 0};
  }
  const uint64_t m = window_margin(spec);
  for (size_t i = 0; i < n_binary; ++i) {
    const uint32_t p = least_period(binary_words[i], binary_lengths[i]);
    const FrequencyCode b = apparent_of_period(spec, static_cast<int64_t>(p) * spec.bit_period_ns);
    for (size_t j = 0; j < n_frequency; ++j) {
      const FrequencyCode f =
          apparent_of_period(spec, static_cast<int64_t>(frequency_lengths[j]) * spec.bit_period_ns);
      if (pair_margin(b, f) < m) {
        return FrequencyReport{FrequencyFault::kTooClose, static_cast<uint16_t>(i), static_cast<uint16_t>(j)};
      }
    }
  }
  return FrequencyReport{};
}

}  // namespace tetrapulse::protocol
