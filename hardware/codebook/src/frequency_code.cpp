#include "tetrapulse/codebook/frequency_code.hpp"


namespace tetrapulse::protocol {

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

namespace {

// A square wave seen through an exposure of E = q C + r ns starting at code
// phase s (any s): lit(s) = q on + (lit time of r ns from s). It is symmetric
// about c = (on - r) / 2, where the r ns are centred on the lit run, and
// non-increasing from c to c + C/2: a trapezoid. So the phases whose exposure
// is lit less than half form one arc of the period, [b, b + d).
struct ExposedWave {
  int64_t C, on, E;

  int64_t phase(int64_t s) const { return ((s % C) + C) % C; }
  int64_t lit(int64_t s) const { return lit_ns(phase(s), E, C, on); }
  bool dark(int64_t s) const { return 2 * lit(s) < E; }
  int64_t brightest() const { return phase((on - E % C) / 2); }
};

}  // namespace

WaveVisibility wave_visibility(const CameraTiming& camera, int64_t bit_period_ns, SquareWave wave,
                               uint32_t dark_cap) {
  WaveVisibility v;
  const int64_t P = camera.frame_period_ns;
  const int64_t E = camera.exposure_ns;
  const ExposedWave w{static_cast<int64_t>(wave.length) * bit_period_ns,
                      static_cast<int64_t>(wave.ones) * bit_period_ns, E};
  if (P <= 0 || E <= 0 || w.C <= 0 || wave.ones == 0 || wave.ones >= wave.length) return v;
  // Extremes: the plateau's centre and the trough's, each +-1 ns for the rounding of c.
  const int64_t c = w.brightest(), half = w.C / 2;
  int64_t brightest = c, darkest = c + half;
  for (int64_t k = -1; k <= 1; ++k) {
    if (w.lit(c + k) > w.lit(brightest)) brightest = c + k;
    if (w.lit(c + half + k) < w.lit(darkest)) darkest = c + half + k;
  }
  v.swing_percent = static_cast<uint32_t>((w.lit(brightest) - w.lit(darkest)) * 100 / E);
  if (w.dark(brightest)) {  // dark at every phase
    v.dark_frames = dark_cap + 1;
    return v;
  }
  if (!w.dark(darkest)) return v;  // never dark
  // b: the first dark phase after the plateau (bisection on the falling side).
  int64_t lo = brightest, hi = darkest;
  while (hi - lo > 1) {
    const int64_t mid = lo + (hi - lo) / 2;
    (w.dark(mid) ? hi : lo) = mid;
  }
  const int64_t b = hi;
  // Any run of dark frames s0 + kP, slid back in phase until one frame reaches
  // the arc's start b, stays dark (frames leave the arc only through b) and may
  // only grow: the longest run is the longest through a frame at phase b,
  // counted forwards and backwards from it. Exact, for every phase at once.
  uint32_t run = 1;
  for (int64_t k = 1; run <= dark_cap && w.dark(b + k * P); ++k) ++run;
  for (int64_t k = 1; run <= dark_cap && w.dark(b - k * P); ++k) ++run;
  v.dark_frames = run;
  return v;
}

}  // namespace tetrapulse::protocol
