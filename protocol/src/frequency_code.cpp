#include "tetrapulse/protocol/frequency_code.hpp"

#include "tetrapulse/protocol/codebook_word.hpp"

namespace tetrapulse::protocol {

uint64_t square_wave_word(SquareWave wave) { return word_mask(wave.ones); }

bool is_square_wave(uint64_t word, uint32_t length, SquareWave* wave) {
  if (length < 2 || length > 64) return false;
  word &= word_mask(length);
  const uint32_t ones = word_weight(word);
  if (ones == 0 || ones == length) return false;
  // One run of each exactly when the 1s form one cyclic run of length `ones`.
  if (max_cyclic_run(word, length, true) != ones) return false;
  if (wave != nullptr) *wave = SquareWave{static_cast<uint8_t>(length), static_cast<uint8_t>(ones)};
  return true;
}

uint64_t ratio_q32(uint64_t a, uint64_t b) {
  if (b == 0 || b >= (uint64_t{1} << 55) || a / b >= (uint64_t{1} << 31)) return ~uint64_t{0};
  uint64_t rem = a % b;
  uint64_t fraction = 0;
  for (int step = 0; step < 4; ++step) {  // long division, one byte of the fraction at a time
    rem <<= 8;
    fraction = (fraction << 8) | (rem / b);
    rem %= b;
  }
  return ((a / b) << 32) | fraction;
}

uint32_t apparent_frequency_q32(int64_t frame_period_ns, int64_t code_period_ns) {
  if (frame_period_ns <= 0 || code_period_ns <= 0) return 0;
  const uint64_t C = static_cast<uint64_t>(code_period_ns);
  const uint64_t r = static_cast<uint64_t>(frame_period_ns) % C;
  const uint64_t nearest = r < C - r ? r : C - r;  // distance of P/C to the nearest integer, times C
  return static_cast<uint32_t>(ratio_q32(nearest, C));
}

uint32_t frequency_drift_q32(int64_t frame_period_ns, int64_t code_period_ns, uint32_t ppm) {
  if (frame_period_ns <= 0 || code_period_ns <= 0) return 0;
  const uint64_t q = ratio_q32(uint64_t{ppm} * static_cast<uint64_t>(frame_period_ns),
                               static_cast<uint64_t>(code_period_ns));
  if (q == ~uint64_t{0}) return ~uint32_t{0};
  const uint64_t drift = q / 1'000'000;  // floor(floor(x) / n) = floor(x / n)
  return drift > 0xFFFFFFFFull ? ~uint32_t{0} : static_cast<uint32_t>(drift);
}

int64_t lit_ns(int64_t start_ns, int64_t duration_ns, int64_t period_ns, int64_t on_ns) {
  auto lit_before = [&](int64_t x) { return (x / period_ns) * on_ns + (x % period_ns < on_ns ? x % period_ns : on_ns); };
  return lit_before(start_ns + duration_ns) - lit_before(start_ns);
}

WaveVisibility wave_visibility(const CameraTiming& camera, int64_t bit_period_ns, SquareWave wave,
                               uint32_t dark_cap) {
  WaveVisibility v;
  const int64_t P = camera.frame_period_ns;
  const int64_t E = camera.exposure_ns;
  const int64_t C = static_cast<int64_t>(wave.length) * bit_period_ns;
  const int64_t on = static_cast<int64_t>(wave.ones) * bit_period_ns;
  if (P <= 0 || E <= 0 || C <= 0) return v;
  int64_t least = E;
  int64_t most = 0;
  for (uint32_t g = 0; g < kPhaseGrid; ++g) {
    // Frame 0 exposed from phase `start` of the code: every frame of every
    // phase is frame 0 of some phase, so a dark run starting at frame 0 is
    // every dark run (up to the grid).
    const int64_t start = C * static_cast<int64_t>(g) / static_cast<int64_t>(kPhaseGrid);
    const int64_t lit = lit_ns(start, E, C, on);
    least = lit < least ? lit : least;
    most = lit > most ? lit : most;
    uint32_t run = 0;
    while (run <= dark_cap && 2 * lit_ns(start + static_cast<int64_t>(run) * P, E, C, on) < E) ++run;
    v.dark_frames = run > v.dark_frames ? run : v.dark_frames;
  }
  v.swing_percent = static_cast<uint32_t>((most - least) * 100 / E);
  return v;
}

}  // namespace tetrapulse::protocol
