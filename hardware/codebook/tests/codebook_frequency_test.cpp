// The frequency family checked against plain floating-point references: apparent
// frequencies, lit time, dark runs, and separability of every chosen pair at the
// extremes of the clock error.
#include "tetrapulse/codebook/codebook_frequency.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr double kQ32 = 4294967296.0;

// Apparent frequency in cycles per frame of a wave of frequency f (Hz) at frame period P (s).
double apparent(double f_hz, double P_s) {
  const double x = f_hz * P_s;
  return std::fabs(x - std::round(x));
}

std::string text(uint64_t w, uint32_t L) {
  std::string s(L, '0');
  for (uint32_t i = 0; i < L; ++i) s[i] = ((w >> i) & 1u) ? '1' : '0';
  return s;
}

// Fraction of [t, t + E) lit by a wave lit over [0, on) of every period C (all seconds), by steps.
double lit_fraction_by_steps(double t, double E, double C, double on) {
  const int steps = 2000;
  int lit = 0;
  for (int i = 0; i < steps; ++i) {
    const double x = std::fmod(t + (i + 0.5) * E / steps, C);
    lit += x < on;
  }
  return static_cast<double>(lit) / steps;
}

FrequencySpec camera_spec(double fps, double exposure_ms) {
  FrequencySpec s;
  s.camera.frame_period_ns = static_cast<int64_t>(std::llround(1e9 / fps));
  s.camera.exposure_ns = static_cast<int64_t>(std::llround(exposure_ms * 1e6));
  return s;
}

TEST(FrequencyCode, ApparentFrequencyFoldsIntoHalfACycle) {
  // 100 fps: a 40 ms period is 1/4 cycle per frame; 12.5 ms is 0.8 -> 0.2; 10 ms is 0; 20 ms is 1/2.
  EXPECT_EQ(apparent_frequency_q32(10'000'000, 40'000'000), uint32_t{1} << 30);
  EXPECT_EQ(apparent_frequency_q32(10'000'000, 12'500'000), static_cast<uint32_t>(0.2 * kQ32));
  EXPECT_EQ(apparent_frequency_q32(10'000'000, 10'000'000), 0u);
  EXPECT_EQ(apparent_frequency_q32(10'000'000, 20'000'000), uint32_t{1} << 31);
}

RC_GTEST_PROP(FrequencyCode, ApparentFrequencyAndDriftMatchDoubles, ()) {
  const int64_t P = *rc::gen::inRange<int64_t>(1'000'000, 100'000'000);
  const int64_t C = *rc::gen::inRange<int64_t>(20'000, int64_t{64} * 50'000'000);
  const uint32_t ppm = *rc::gen::inRange<uint32_t>(0, 1000);
  const double nu = apparent(1.0 / static_cast<double>(C), static_cast<double>(P));
  RC_ASSERT(std::fabs(apparent_frequency_q32(P, C) - nu * kQ32) <= 2.0);
  const double drift = ppm * 1e-6 * static_cast<double>(P) / static_cast<double>(C);
  RC_ASSERT(std::fabs(frequency_drift_q32(P, C, ppm) - drift * kQ32) <= 2.0);
}

RC_GTEST_PROP(FrequencyCode, LitTimeMatchesStepwiseIntegration, ()) {
  const int64_t C = *rc::gen::inRange<int64_t>(2, 5000);
  const int64_t on = *rc::gen::inRange<int64_t>(0, C + 1);
  const int64_t start = *rc::gen::inRange<int64_t>(0, 20'000);
  const int64_t E = *rc::gen::inRange<int64_t>(0, 12'000);
  int64_t expected = 0;
  for (int64_t t = start; t < start + E; ++t) expected += (t % C) < on;
  RC_ASSERT(lit_ns(start, E, C, on) == expected);
}

TEST(FrequencyCode, SquareWavesAreOneRunOfEach) {
  SquareWave w;
  EXPECT_TRUE(is_square_wave(Code{7, 0b0111000}, &w));  // "0001110": rotation of "1110000"
  EXPECT_EQ(w.length, 7);
  EXPECT_EQ(w.ones, 3);
  EXPECT_TRUE(is_square_wave(Code{7, 0b1000001}, &w));  // wraps around
  EXPECT_EQ(w.ones, 2);
  EXPECT_FALSE(is_square_wave(Code{4, 0b0101}, nullptr));  // "1010": two runs of each
  EXPECT_FALSE(is_square_wave(Code{4, 0b1111}, nullptr));
  EXPECT_FALSE(is_square_wave(Code{4, 0}, nullptr));
  EXPECT_FALSE(is_square_wave(Code{1, 0b1}, nullptr));
  EXPECT_EQ(text(square_wave_word(SquareWave{6, 3}), 6), "111000");
}

RC_GTEST_PROP(FrequencyCode, DarkRunsOfAnyPhaseNeverExceedTheReport, ()) {
  const FrequencySpec s = camera_spec(*rc::gen::inRange(30, 240), *rc::gen::inRange(1, 20) * 0.25);
  RC_PRE(s.camera.exposure_ns <= s.camera.frame_period_ns);
  const int64_t T = *rc::gen::inRange<int64_t>(100'000, 20'000'000);
  const uint8_t L = *rc::gen::inRange<uint8_t>(2, 65);
  const uint8_t ones = *rc::gen::inRange<uint8_t>(1, L);
  const WaveVisibility v = wave_visibility(s.camera, T, SquareWave{L, ones}, 1000);
  // Frames of one random (off-grid) phase, by steps, in seconds.
  const double P = s.camera.frame_period_ns * 1e-9, E = s.camera.exposure_ns * 1e-9;
  const double C = L * T * 1e-9, on = ones * T * 1e-9;
  const double phase = *rc::gen::inRange(0, 1000000) * 1e-6 * C;
  uint32_t run = 0, longest = 0;
  for (int k = 0; k < 200; ++k) {
    run = lit_fraction_by_steps(phase + k * P, E, C, on) < 0.5 - 1e-3 ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  // The report is exact over every phase (the steps count a frame lit within
  // 1e-3 of half as lit, so they may only see less).
  RC_ASSERT(longest <= v.dark_frames);
}

// On small integer timings every phase can be tried: the report is the longest
// dark run exactly, and the swing the exact spread of the lit time.
RC_GTEST_PROP(FrequencyCode, DarkRunsAndSwingEqualAnExhaustiveSearch, ()) {
  const int64_t T = *rc::gen::inRange<int64_t>(1, 40);
  const uint8_t L = *rc::gen::inRange<uint8_t>(2, 13);
  const uint8_t ones = *rc::gen::inRange<uint8_t>(1, L);
  const int64_t P = *rc::gen::inRange<int64_t>(1, 600);
  const int64_t E = *rc::gen::inRange<int64_t>(1, P + 1);
  constexpr uint32_t kCap = 40;
  const WaveVisibility v = wave_visibility(CameraTiming{P, E}, T, SquareWave{L, ones}, kCap);
  const int64_t C = L * T, on = ones * T;
  uint32_t longest = 0;
  int64_t most = 0, least = E;
  for (int64_t s0 = 0; s0 < C; ++s0) {
    const int64_t lit = lit_ns(s0, E, C, on);
    most = std::max(most, lit);
    least = std::min(least, lit);
    uint32_t run = 0;
    while (run <= kCap && 2 * lit_ns(s0 + run * P, E, C, on) < E) ++run;
    longest = std::max(longest, run);
  }
  RC_ASSERT(v.dark_frames == longest);
  RC_ASSERT(v.swing_percent == static_cast<uint32_t>((most - least) * 100 / E));
}

TEST(CodebookFrequency, HundredFpsSeparatesAtLeastEight) {
  for (double exposure_ms : {0.5, 1.0, 2.0, 5.0}) {
    FrequencySpec s = camera_spec(100, exposure_ms);
    s.count = 8;
    FrequencyCodebook book;
    ASSERT_TRUE(choose_frequency_codes(s, &book).ok());
    EXPECT_GE(book.capacity, 8u) << exposure_ms << " ms";
    EXPECT_EQ(book.count, 8u) << exposure_ms << " ms";
    EXPECT_GE(uint64_t{book.margin_q32}, kCyclePerFrameQ32 / s.window_frames);
  }
}

TEST(CodebookFrequency, RefusesMoreThanTheCameraSeparatesAndSaysTheMost) {
  FrequencySpec s = camera_spec(100, 1.0);
  s.count = 63;
  FrequencyCodebook book;
  ASSERT_TRUE(choose_frequency_codes(s, &book).ok());
  EXPECT_EQ(book.count, 0u);
  ASSERT_GT(book.capacity, 0u);
  ASSERT_LT(book.capacity, 63u);
  // Exactly the capacity is granted, one more is not.
  s.count = static_cast<uint16_t>(book.capacity);
  FrequencyCodebook most;
  ASSERT_TRUE(choose_frequency_codes(s, &most).ok());
  EXPECT_EQ(most.count, book.capacity);
  s.count = static_cast<uint16_t>(book.capacity + 1);
  FrequencyCodebook over;
  ASSERT_TRUE(choose_frequency_codes(s, &over).ok());
  EXPECT_EQ(over.count, 0u);
  EXPECT_EQ(over.capacity, book.capacity);
}

TEST(CodebookFrequency, LongerWindowsSeparateMore) {
  uint32_t previous = 0;
  for (uint16_t W : {12, 16, 24, 32, 48}) {
    FrequencySpec s = camera_spec(100, 1.0);
    s.window_frames = W;
    s.count = 1;
    FrequencyCodebook book;
    ASSERT_TRUE(choose_frequency_codes(s, &book).ok());
    EXPECT_GE(book.capacity, previous) << W;
    EXPECT_LE(book.capacity, W / 2u) << W;  // 1/W apart within (0, 1/2)
    previous = book.capacity;
  }
}

TEST(CodebookFrequency, BadSpecsAreRefused) {
  FrequencySpec s = camera_spec(100, 1.0);
  FrequencyCodebook book;
  s.camera.exposure_ns = s.camera.frame_period_ns + 1;
  EXPECT_NE(check_frequency_spec(s), nullptr);
  EXPECT_FALSE(choose_frequency_codes(s, &book).ok());
  s = camera_spec(100, 1.0);
  s.count = 0;
  EXPECT_FALSE(choose_frequency_codes(s, &book).ok());
  s = camera_spec(100, 1.0);
  s.bit_period_ns = 5;
  EXPECT_FALSE(choose_frequency_codes(s, &book).ok());
}

TEST(CodebookFrequency, CheckFindsTheFaults) {
  FrequencySpec s = camera_spec(100, 1.0);
  s.bit_period_ns = 10'000'000;  // one bit per frame: "110" is 1/3 cycle per frame
  const uint64_t good[] = {0b011, 0b0111};  // "110", "1110"
  const uint8_t good_len[] = {3, 4};
  EXPECT_TRUE(check_frequency_codes(s, good, good_len, 2).ok());
  const uint64_t wave[] = {0b0101};  // "1010" is not a square wave
  const uint8_t wave_len[] = {4};
  EXPECT_EQ(check_frequency_codes(s, wave, wave_len, 1).fault, FrequencyFault::kNotSquareWave);
  const uint64_t nyquist[] = {0b01};  // "10" at one bit per frame: 1/2 cycle per frame
  const uint8_t nyquist_len[] = {2};
  EXPECT_EQ(check_frequency_codes(s, nyquist, nyquist_len, 1).fault, FrequencyFault::kNearNyquist);
  const uint64_t slow[] = {square_wave_word(SquareWave{60, 58})};  // 1/60 cycle per frame < 1/24
  const uint8_t slow_len[] = {60};
  EXPECT_EQ(check_frequency_codes(s, slow, slow_len, 1).fault, FrequencyFault::kNearConstant);
  const uint64_t dark[] = {square_wave_word(SquareWave{12, 6})};  // six dark frames in a row
  const uint8_t dark_len[] = {12};
  EXPECT_EQ(check_frequency_codes(s, dark, dark_len, 1).fault, FrequencyFault::kTooDark);
  s.bit_period_ns = 2'500'000;  // 1/(7 T) = 57.1 Hz -> 0.429; 1/(9 T) = 44.4 Hz -> 0.444 apart by 0.016 < 1/24
  const uint64_t close[] = {square_wave_word(SquareWave{7, 4}), square_wave_word(SquareWave{9, 5})};
  const uint8_t close_len[] = {7, 9};
  const FrequencyReport r = check_frequency_codes(s, close, close_len, 2);
  EXPECT_EQ(r.fault, FrequencyFault::kTooClose);
  EXPECT_EQ(r.other, 1);
}

// Binary words beside square waves: a word is seen at the apparent frequency of
// its least period, and must keep 1/W (plus drifts) from every square wave.
TEST(CodebookFrequency, BinaryWordsBesideSquareWavesKeepTheirApparentFrequencyApart) {
  FrequencySpec s = camera_spec(100, 1.0);
  s.bit_period_ns = 2'500'000;  // "1110000" (7 bits): 17.5 ms, 0.429 cycle per frame
  const uint64_t freq[] = {square_wave_word(SquareWave{7, 3})};
  const uint8_t freq_len[] = {7};
  // 12 bits: 30 ms, 1/3 cycle per frame, 0.095 from 0.429 > 1/24: apart.
  const uint64_t apart[] = {0b101100111010};
  const uint8_t apart_len[] = {12};
  EXPECT_TRUE(check_binary_beside_frequency(s, apart, apart_len, 1, freq, freq_len, 1).ok());
  // "111000011100001110000" has least period 7: "1110000" again, 21 bits or not.
  const uint64_t same[] = {apart[0], 0b000011100001110000111};
  const uint8_t same_len[] = {12, 21};
  const FrequencyReport r = check_binary_beside_frequency(s, same, same_len, 2, freq, freq_len, 1);
  EXPECT_EQ(r.fault, FrequencyFault::kTooClose);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.other, 0);
  // 9 bits: 22.5 ms, 0.444 cycle per frame, 0.016 from 0.429 < 1/24.
  const uint64_t near[] = {0b110100011};
  const uint8_t near_len[] = {9};
  EXPECT_EQ(check_binary_beside_frequency(s, near, near_len, 1, freq, freq_len, 1).fault, FrequencyFault::kTooClose);
  s.bit_period_ns = 0;
  EXPECT_EQ(check_binary_beside_frequency(s, apart, apart_len, 1, freq, freq_len, 1).fault, FrequencyFault::kBadSpec);
}

// The rule matches the apparent frequencies in doubles: whenever the check passes,
// every clock error within +-ppm leaves the binary word's and each square wave's
// apparent frequencies 1/W apart.
RC_GTEST_PROP(CodebookFrequency, BinaryWordsThatPassStayApartUnderClockError, ()) {
  FrequencySpec s = camera_spec(*rc::gen::inRange(20, 400), 1.0);
  s.bit_period_ns = *rc::gen::inRange<int64_t>(10'000, 5'000'000);
  s.window_frames = *rc::gen::inRange<uint16_t>(8, 64);
  const uint8_t L = *rc::gen::inRange<uint8_t>(2, 65);
  const uint64_t binary[] = {*rc::gen::arbitrary<uint64_t>() & word_mask(L)};
  const uint8_t binary_len[] = {L};
  const uint8_t F = *rc::gen::inRange<uint8_t>(2, 65);
  const uint64_t freq[] = {square_wave_word(SquareWave{F, static_cast<uint8_t>(F / 2)})};
  const uint8_t freq_len[] = {F};
  const bool apart = check_binary_beside_frequency(s, binary, binary_len, 1, freq, freq_len, 1).ok();
  RC_CLASSIFY(apart, "apart");
  const double P = s.camera.frame_period_ns * 1e-9;
  const double fb = 1.0 / (least_period(binary[0], L) * s.bit_period_ns * 1e-9);
  const double ff = 1.0 / (F * s.bit_period_ns * 1e-9);
  double least_gap = 1;
  for (double eb : {-1.0, 1.0}) {
    for (double ef : {-1.0, 1.0}) {
      least_gap = std::min(least_gap, std::fabs(apparent(fb * (1 + eb * s.clock_ppm * 1e-6), P) -
                                                apparent(ff * (1 + ef * s.clock_ppm * 1e-6), P)));
    }
  }
  if (apart) RC_ASSERT(least_gap >= (1.0 / s.window_frames) * (1 - 1e-6));
  // And the rule is not much stricter than that: a gap of twice the margin plus the drifts passes.
  const double drifts = s.clock_ppm * 1e-6 * P * (fb + ff);
  const double nominal = std::fabs(apparent(fb, P) - apparent(ff, P));
  if (nominal >= 1.0 / s.window_frames + drifts + 1e-6) RC_ASSERT(apart);
}

// Every chosen set, for any camera that can meet the request: each code a square
// wave, distinct from every other under every shift, and every pair's apparent
// frequencies 1/W apart at every combination of clock errors within +-ppm.
RC_GTEST_PROP(CodebookFrequency, ChosenPairsStaySeparableUnderClockError, ()) {
  FrequencySpec s = camera_spec(*rc::gen::inRange(20, 400), *rc::gen::inRange(1, 40) * 0.25);
  RC_PRE(s.camera.exposure_ns <= s.camera.frame_period_ns);
  s.window_frames = *rc::gen::inRange<uint16_t>(8, 64);
  s.clock_ppm = *rc::gen::element(100u, 200u, 500u);
  s.max_dark_frames = *rc::gen::element<uint8_t>(2, 3, 4, kNoDarkLimit);
  s.count = *rc::gen::inRange<uint16_t>(1, 13);
  FrequencyCodebook book;
  RC_ASSERT(choose_frequency_codes(s, &book).ok());
  RC_PRE(book.count > 0);
  RC_ASSERT(book.count == s.count);
  const double P = s.camera.frame_period_ns * 1e-9;
  const double m = 1.0 / s.window_frames;
  std::vector<std::string> necklaces;
  for (uint32_t i = 0; i < book.count; ++i) {
    const FrequencyCode& c = book.codes[i];
    RC_ASSERT(is_square_wave(Code{c.wave.length, c.word}, nullptr));
    if (s.max_dark_frames != kNoDarkLimit) RC_ASSERT(c.visibility.dark_frames <= s.max_dark_frames);
    RC_ASSERT(c.visibility.swing_percent >= s.min_swing_percent);
    necklaces.push_back(text(least_rotation(c.word, c.wave.length), c.wave.length));
    const double f = 1.0 / (c.wave.length * book.bit_period_ns * 1e-9);
    for (double e : {-1.0, 1.0}) {
      const double nu = apparent(f * (1 + e * s.clock_ppm * 1e-6), P);
      RC_ASSERT(nu >= m * (1 - 1e-6));
      RC_ASSERT(0.5 - nu >= m / 2 * (1 - 1e-6));
    }
    for (uint32_t j = 0; j < i; ++j) {
      const double g = 1.0 / (book.codes[j].wave.length * book.bit_period_ns * 1e-9);
      for (double ei : {-1.0, 1.0}) {
        for (double ej : {-1.0, 1.0}) {
          const double gap = std::fabs(apparent(f * (1 + ei * s.clock_ppm * 1e-6), P) -
                                       apparent(g * (1 + ej * s.clock_ppm * 1e-6), P));
          RC_ASSERT(gap >= m * (1 - 1e-6));
        }
      }
    }
  }
  std::sort(necklaces.begin(), necklaces.end());
  RC_ASSERT(std::adjacent_find(necklaces.begin(), necklaces.end()) == necklaces.end());
  // Its own check agrees.
  std::vector<uint64_t> words;
  std::vector<uint8_t> lengths;
  for (uint32_t i = 0; i < book.count; ++i) {
    words.push_back(book.codes[i].word);
    lengths.push_back(book.codes[i].wave.length);
  }
  FrequencySpec fixed = s;
  fixed.bit_period_ns = book.bit_period_ns;
  RC_ASSERT(check_frequency_codes(fixed, words.data(), lengths.data(), words.size()).ok());
}

}  // namespace
}  // namespace tetrapulse::protocol
