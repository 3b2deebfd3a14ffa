// Reading a track's samples as bits with levels that follow the marker's light.
#include "tetrapulse/localizer/track_bits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tetrapulse {
namespace {

// Samples of a marker playing `bits` (one per frame) at relative level `low` in
// a 0 bit, whose full intensity follows `brightness(k)`, with relative noise.
RingBuffer<TrackSample, kTrackHistory> samples(const std::string& bits, double low, double (*brightness)(int),
                                               double noise, uint64_t seed, bool on_off = false) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  RingBuffer<TrackSample, kTrackHistory> h;
  for (size_t k = 0; k < bits.size(); ++k) {
    TrackSample s;
    s.frame = int64_t(k);
    const double level = bits[k] == '1' ? 1.0 : low;
    s.intensity = brightness(int(k)) * (level + noise * g(rng));
    s.measured = true;
    s.detected = !on_off || bits[k] == '1';
    h.push(s);
  }
  return h;
}

std::string read(const RingBuffer<TrackSample, kTrackHistory>& h, const Modulation& m) {
  TrackBits bits;
  read_track_bits(h, m, BitReading{}, 0, &bits);
  std::string out;
  for (size_t j = 0; j < h.size(); ++j) out += bits[j] == ReadBit::kOne ? '1' : bits[j] == ReadBit::kZero ? '0' : '?';
  return out;
}

double steady(int) { return 5000; }
// The camera closing in from 1.7 m to 0.7 m over 60 frames: 6 times brighter.
double approaching(int k) {
  const double d = 1.7 - 1.0 * k / 60.0;
  return 5000 / (d * d);
}

const std::string kBits = "010011100101010011100101010011100101010011100101010011100101";

TEST(TrackBits, TwoLevelReadsEveryBitOnceBothLevelsShowed) {
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  EXPECT_EQ(read(samples(kBits, 0.3, steady, 0.02, 1), m), kBits);
}

TEST(TrackBits, TwoLevelFollowsAMarkerGrowingSixTimesBrighter) {
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  EXPECT_EQ(read(samples(kBits, 0.3, approaching, 0.02, 2), m), kBits);
}

TEST(TrackBits, TwoLevelRunOfOnesIsUnknownNotGuessed) {
  // A new track that has only seen 1s cannot tell them from 0s.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  EXPECT_EQ(read(samples("111", 0.3, steady, 0.0, 3), m), "???");
  EXPECT_EQ(read(samples("000", 0.3, steady, 0.0, 3), m), "???");
  EXPECT_EQ(read(samples("1110", 0.3, steady, 0.0, 3), m), "1110");
}

TEST(TrackBits, OnOffDarkIsAZeroFromTheStart) {
  const Modulation m{ModulationKind::kOnOff, 0};
  EXPECT_EQ(read(samples("1100", 0.0, steady, 0.01, 4, true), m), "1100");
  EXPECT_EQ(read(samples(kBits, 0.0, approaching, 0.01, 5, true), m), kBits);
}

TEST(TrackBits, IntermediateLevelIsUnknown) {
  // An exposure half in a 1 and half in a 0 reads (1 + 0.3) / 2.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  auto h = samples("10101", 0.3, steady, 0.0, 6);
  h[2].intensity = 5000 * 0.65;
  EXPECT_EQ(read(h, m), "10?01");
}

TEST(TrackBits, UnmeasuredSamplesAreUnknown) {
  const Modulation m{ModulationKind::kOnOff, 0};
  auto h = samples("1101", 0.0, steady, 0.0, 7, true);
  h[2].measured = false;
  EXPECT_EQ(read(h, m), "11?1");
}

TEST(TrackBits, ConstantModulationReadsOnes) {
  EXPECT_EQ(read(samples("1111", 1.0, steady, 0.05, 8), Modulation{ModulationKind::kConstant, 0}), "1111");
}

TEST(TrackBits, NoiseRarelyFlipsABit) {
  // 5 % intensity noise (a marker of a few pixels): errors, if any, are rare and
  // most doubtful readings are unknown rather than wrong.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  int wrong = 0, unknown = 0;
  for (uint64_t seed = 0; seed < 100; ++seed) {
    const std::string got = read(samples(kBits, 0.3, approaching, 0.05, 100 + seed), m);
    for (size_t i = 0; i < kBits.size(); ++i) {
      wrong += got[i] != '?' && got[i] != kBits[i];
      unknown += got[i] == '?';
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(unknown, 60);  // of 6000
}

// What a sensor leaves of a marker's light, r = relative emission in 0..1 at the
// brightest: clipped at full scale by a radiance `overexposure` times full scale
// (the clipped sum still grows a little with the light: the ring of pixels it
// adds), or encoded with a gamma of 1/2.2 as video cameras do.
RingBuffer<TrackSample, kTrackHistory> compressed(const std::string& bits, double low, double (*brightness)(int),
                                                  double noise, uint64_t seed, double (*response)(double),
                                                  bool saturated) {
  auto h = samples(bits, low, brightness, noise, seed);
  for (size_t j = 0; j < h.size(); ++j) {
    const double scale = brightness(int(j));
    h[j].intensity = scale * response(std::max(0.0, h[j].intensity / scale));
    h[j].saturated = saturated;
  }
  return h;
}
// A disc clipped at 10x overexposure: its sum grows by the rim the PSF adds,
// about 1 + 0.03 ln(radiance) (0.3 reads 0.87 of 1).
double clipped(double r) { return 1 + 0.11 * std::log(std::max(r, 1e-3)); }
double gamma_encoded(double r) { return std::pow(r, 1 / 2.2); }

TEST(TrackBits, SaturatedTwoLevelIsReadFromTheLevelsItShows) {
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  // 0.3 reads as 0.87 of a 1: the nominal levels read nothing.
  EXPECT_EQ(read(compressed(kBits, 0.3, steady, 0.005, 11, clipped, true), m), kBits);
}

TEST(TrackBits, SaturatedTwoLevelFollowsAMarkerClosingIn) {
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  const std::string got = read(compressed(kBits, 0.3, approaching, 0.005, 12, clipped, true), m);
  int wrong = 0, unknown = 0;
  for (size_t i = 0; i < kBits.size(); ++i) wrong += got[i] != '?' && got[i] != kBits[i], unknown += got[i] == '?';
  EXPECT_EQ(wrong, 0) << got;
  EXPECT_LE(unknown, 2) << got;
}

// A drone landing: 1.2 m to 0.36 m at constant speed over 60 frames, 11 times
// brighter and ever faster (7 % a frame at the end).
double landing(int k) {
  const double d = 1.2 - 0.84 * k / 59.0;
  return 5000 / (d * d);
}
// A large clipped disc: its 0.3 level reads only 0.95 of its 1.
double barely_clipped(double r) { return 1 + 0.042 * std::log(std::max(r, 1e-3)); }

TEST(TrackBits, SaturatedTwoLevelFollowsALightGrowingEverFaster) {
  // Under the drift of a line, the window's curvature (a few % over 17 samples)
  // is as large as the code's contrast; under a parabola it is gone.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  const std::string got = read(compressed(kBits, 0.3, landing, 0.003, 15, barely_clipped, true), m);
  int wrong = 0, unknown = 0;
  for (size_t i = 0; i < kBits.size(); ++i) wrong += got[i] != '?' && got[i] != kBits[i], unknown += got[i] == '?';
  EXPECT_EQ(wrong, 0) << got;
  EXPECT_LE(unknown, 4) << got;
}

TEST(TrackBits, GammaEncodedTwoLevelIsRead) {
  // 0.3 reads 0.58 of a 1, inside the nominal levels' unknown band.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  EXPECT_EQ(read(compressed(kBits, 0.3, approaching, 0.01, 13, gamma_encoded, false), m), kBits);
}

TEST(TrackBits, SaturatedRunOfOnesClosingInIsUnknown) {
  // A drift of the level is no code: a marker that only shows 1s while it grows
  // 6 times brighter reads nothing.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  const std::string ones(60, '1');
  const std::string got = read(compressed(ones, 0.3, approaching, 0.005, 14, clipped, true), m);
  EXPECT_EQ(got.find('0'), std::string::npos) << got;
}

// A track's samples as the tracker leaves them: a marker playing random bits,
// noisy enough for doubtful readings, sometimes missed (measured from the
// aperture or not at all).
TrackSample random_sample(int64_t frame, const Modulation& m, double brightness, std::mt19937_64* rng,
                          double ones = 0.5) {
  std::uniform_real_distribution<double> u(0, 1);
  TrackSample s;
  s.frame = frame;
  const bool one = u(*rng) < ones;
  const double level = one ? 1.0 : m.kind == ModulationKind::kOnOff ? 0.0 : m.low;
  s.measured = u(*rng) > 0.1;
  s.detected = s.measured && (one || m.kind != ModulationKind::kOnOff) && u(*rng) > 0.1;
  s.intensity = s.measured ? brightness * (1 + 0.3 * u(*rng)) * std::max(0.0, level + 0.3 * (u(*rng) - 0.5)) : 0.0;
  return s;
}

TEST(TrackBitReader, KeepsWhatAFullReadReadsFrameAfterFrame) {
  // 300 frames (the history drops its oldest sample from frame 64 on), a reader
  // that asks for more or fewer samples now and then, windows from 1 to wider
  // than half the history, three modulations, codes with as many 1s as 0s and
  // with few 1s (levels then come from far in the window): every frame, the
  // kept bits equal a fresh full read. Some of the cases this guards against
  // show once in a hundred tracks, hence so many.
  const Modulation modulations[] = {{ModulationKind::kTwoLevel, 0.3}, {ModulationKind::kOnOff, 0.0},
                                    {ModulationKind::kConstant, 0.0}};
  int64_t compared = 0;
  for (const Modulation& m : modulations)
    for (const int window : {1, 2, 3, 4, 6, 8, 40})
      for (uint64_t seed = 0; seed < 100; ++seed) {
        std::mt19937_64 rng(seed * 31 + uint64_t(window));
        const double ones = seed % 2 == 0 ? 0.5 : 0.15;
        const BitReading reading{window, 0.15};
        RingBuffer<TrackSample, kTrackHistory> history;
        TrackBitReader reader;
        int samples = 48;
        for (int64_t frame = 0; frame < 300; ++frame) {
          history.push(random_sample(frame, m, 3000.0 * (1.0 + 0.5 * std::sin(0.05 * double(frame))), &rng, ones));
          if (rng() % 3 == 0) samples = int(rng() % (kTrackHistory + 1));  // e.g. a track claimed or let go
          const size_t n = history.size();
          const size_t from = n > size_t(samples) ? n - size_t(samples) : 0;
          reader.update(history, m, reading, from);
          TrackBits fresh;
          read_track_bits(history, m, reading, from, &fresh);
          for (size_t j = from; j < n; ++j) {
            ASSERT_EQ(reader.bits()[j], fresh[j]) << "window " << window << ", seed " << seed << ", frame " << frame
                                                  << ", sample " << j << " of " << n;
            ++compared;
          }
        }
      }
  EXPECT_GT(compared, 10000000);
}

TEST(TrackBitReader, FollowsUpdatesThatSkipSamples) {
  // Frame numbers with gaps, and updates after 1 to 80 new samples: after more
  // than a whole history the reader starts over; every time it reads as a full read.
  const Modulation m{ModulationKind::kTwoLevel, 0.3};
  std::mt19937_64 rng(7);
  RingBuffer<TrackSample, kTrackHistory> h;
  TrackBitReader reader;
  int64_t frame = 0;
  for (int update = 0; update < 200; ++update) {
    const int fresh_samples = update % 25 == 24 ? 80 : 1 + int(rng() % 6);
    for (int k = 0; k < fresh_samples; ++k) h.push(random_sample(frame += 1 + int64_t(rng() % 3), m, 4000, &rng));
    reader.update(h, m, BitReading{}, 0);
    TrackBits fresh;
    read_track_bits(h, m, BitReading{}, 0, &fresh);
    for (size_t j = 0; j < h.size(); ++j) ASSERT_EQ(reader.bits()[j], fresh[j]) << "update " << update << ", sample " << j;
  }
}

}  // namespace
}  // namespace tetrapulse
