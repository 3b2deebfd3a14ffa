#include "tetrapulse/localizer/code_clock.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {

namespace {

int64_t floor_div(int64_t a, int64_t b) {
  const int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

}  // namespace

int64_t CodeClock::bit_number(int64_t t_ns) const {
  const int64_t d = t_ns - origin_ns;
  if (rate == 1.0) return floor_div(d, bit_period_ns);  // exact for synchronized boards
  return static_cast<int64_t>(std::floor(double(d) * rate / double(bit_period_ns)));
}

ExpectedBit expected_bit(const CodeClock& clock, const Code& code, int64_t start_ns, int64_t exposure_ns) {
  const int64_t span = std::max<int64_t>(exposure_ns, 1) - 1;
  int64_t first, last;
  if (clock.rate == 1.0) {
    // The bit of the exposure's end from the start's remainder: one division, not
    // two (code checks ask this of every sample of every track, every frame).
    const int64_t d = start_ns - clock.origin_ns;
    first = floor_div(d, clock.bit_period_ns);
    const int64_t into = d - first * clock.bit_period_ns;  // in [0, period)
    last = into + span < clock.bit_period_ns ? first : first + floor_div(into + span, clock.bit_period_ns);
  } else {
    first = clock.bit_number(start_ns);
    last = clock.bit_number(start_ns + span);
  }
  const int64_t L = code.length;
  const auto index = [L](int64_t n) {
    const int64_t m = n % L;
    return static_cast<uint32_t>(m < 0 ? m + L : m);
  };
  const bool value = code.bit(index(first));
  // An exposure spanning a whole code cycle or more integrates both values (if the code has both).
  for (int64_t n = first + 1; n <= last && n <= first + L; ++n)
    if (code.bit(index(n)) != value) return ExpectedBit::kMixed;
  return value ? ExpectedBit::kOne : ExpectedBit::kZero;
}

double mean_emission(const CodeClock& clock, const Modulation& modulation, const std::optional<Code>& code,
                     int64_t start_ns, int64_t exposure_ns) {
  if (!code || code->length == 0 || modulation.kind == ModulationKind::kConstant || exposure_ns <= 0) return 1.0;
  const double zero = modulation.kind == ModulationKind::kTwoLevel ? modulation.low : 0.0;
  const int64_t L = code->length;
  double total = 0;
  int64_t t = start_ns;
  const int64_t end = start_ns + exposure_ns;
  while (t < end) {
    const int64_t n = clock.bit_number(t);
    // The next edge, found by stepping (clock rates are within 200 ppm of 1).
    int64_t edge = clock.origin_ns + int64_t(double(n + 1) * double(clock.bit_period_ns) / clock.rate);
    while (clock.bit_number(edge) <= n) ++edge;
    while (edge - 1 > t && clock.bit_number(edge - 1) > n) --edge;
    const int64_t piece_end = std::min(edge, end);
    total += double(piece_end - t) * (code->bit(uint32_t(((n % L) + L) % L)) ? 1.0 : zero);
    t = piece_end;
  }
  return total / double(exposure_ns);
}

}  // namespace tetrapulse
