// FrequencyIdentifier on synthetic tracks: boards on their own crystal (up to
// 200 ppm off, unknown phase), a camera integrating each exposure, noise, slow
// changes of brightness and dropped frames. The codes are the frequency
// codebook's for a 100 fps camera; binary codes share the rig in one test.
#include "tetrapulse/localizer/frequency_identifier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "tetrapulse/codebook/codebook_frequency.hpp"

namespace tetrapulse {
namespace {

constexpr int64_t kFramePeriod = 10'000'000;  // 100 fps
constexpr int64_t kExposure = 1'000'000;

// A board playing `code` on its own clock: board time b(t) = origin + (1 + ppm 1e-6) t.
struct Board {
  Code code;
  int64_t bit_period_ns = 0;
  double ppm = 0;
  double origin_ns = 0;
  ModulationKind modulation = ModulationKind::kOnOff;
  double low = 0.3;

  // Mean emission over [t, t + E), integrated in 256 steps (an independent reference).
  double emission(int64_t t, int64_t E) const {
    const int steps = 256;
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
      const double rig = static_cast<double>(t) + (i + 0.5) * static_cast<double>(E) / steps;
      const double b = origin_ns + (1 + ppm * 1e-6) * rig;
      const auto n = static_cast<int64_t>(std::floor(b / static_cast<double>(bit_period_ns)));
      const bool one = code.bit(static_cast<uint32_t>(((n % code.length) + code.length) % code.length));
      sum += one ? 1.0 : (modulation == ModulationKind::kTwoLevel ? low : 0.0);
    }
    return sum / steps;
  }
};

struct StreamOptions {
  int frames = 100;
  double drop = 0.1;     // probability a frame is dropped
  double noise = 0.03;   // sigma, fraction of full brightness
  uint64_t seed = 1;
};

struct StreamResult {
  int first_decision = -1;  // frame of the first decision (any kind), -1: none
  int decided_frames = 0;
  int wrong = 0;            // frames whose decision names another code or family
  int final_code = -1;
};

// Plays `board` into a fresh identifier frame by frame; `expected` is the index
// in codes() it must decide for (-1: it must never decide).
StreamResult run_stream(const TargetsFile& rig, const Board& board, int expected, const StreamOptions& o,
                        FrequencyDecision::Kind expected_kind = FrequencyDecision::Kind::kFrequency) {
  FrequencyIdentifier id(rig);
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, o.noise);
  const double base = 1000 * (0.5 + u(rng));
  StreamResult r;
  for (int k = 0; k < o.frames; ++k) {
    if (u(rng) < o.drop) continue;
    const int64_t start = 123'456'789 + k * kFramePeriod;
    const double brightness = base * (1 + 0.2 * std::sin(k / 40.0));  // moving closer and away
    const double intensity = brightness * (board.emission(start, kExposure) + noise(rng)) + 5;
    id.push(FrequencySample{start, kExposure, intensity});
    const FrequencyDecision& d = id.decision();
    if (!d.decided()) continue;
    if (r.first_decision < 0) r.first_decision = k;
    ++r.decided_frames;
    if (d.code != expected || d.kind != expected_kind) ++r.wrong;
    r.final_code = d.code;
  }
  return r;
}

protocol::FrequencyCodebook codebook_100fps(uint16_t count) {
  protocol::FrequencySpec s;
  s.camera = protocol::CameraTiming{kFramePeriod, kExposure};
  s.count = count;
  protocol::FrequencyCodebook book;
  EXPECT_TRUE(protocol::choose_frequency_codes(s, &book).ok());
  EXPECT_EQ(book.count, count);
  return book;
}

// One target per code, all four markers playing it (the code names the target).
TargetsFile rig_of(const protocol::FrequencyCodebook& book, bool synchronized) {
  TargetsFile rig;
  rig.timebase.synchronized = synchronized;
  rig.timebase.bit_period_ns = book.bit_period_ns;
  for (uint32_t i = 0; i < book.count; ++i) {
    Target t;
    t.id = static_cast<int>(i) + 1;
    for (Marker& m : t.markers) m.code = Code{book.codes[i].wave.length, book.codes[i].word};
    rig.targets.push_back(t);
  }
  return rig;
}

// Frames in the longest apparent period of the book.
double longest_apparent_period(const protocol::FrequencyCodebook& book) {
  uint32_t slowest = ~0u;
  for (uint32_t i = 0; i < book.count; ++i) slowest = std::min(slowest, book.codes[i].apparent_q32);
  return 4294967296.0 / slowest;
}

TEST(FrequencyIdentifier, FindsTheSquareWavesOfARig) {
  TargetsFile rig;
  rig.timebase.synchronized = false;
  Target t;
  t.markers[0].code = *parse_code("111000", nullptr);
  t.markers[1].code = *parse_code("011100", nullptr);  // a rotation: the same code free-running
  t.markers[2].code = *parse_code("10", nullptr);
  t.markers[3].code = *parse_code("110100", nullptr);  // two runs of 1s: binary
  rig.targets.push_back(t);
  const std::vector<RigCode> codes = rig_codes(rig);
  ASSERT_EQ(codes.size(), 3u);
  EXPECT_TRUE(codes[0].frequency);
  EXPECT_EQ(codes[0].markers.size(), 2u);
  EXPECT_TRUE(codes[1].frequency);
  EXPECT_FALSE(codes[2].frequency);
  rig.timebase.synchronized = true;  // with a known phase a rotation is another code
  EXPECT_EQ(rig_codes(rig).size(), 4u);
}

// Every code of the 100 fps codebook, free-running at a random phase and rate,
// with 10 % of frames dropped: identified within two of the book's longest
// apparent periods, never as another code.
TEST(FrequencyIdentifier, IdentifiesEveryCodeFreeRunningWithinTwoLongestPeriods) {
  const protocol::FrequencyCodebook book = codebook_100fps(8);
  const TargetsFile rig = rig_of(book, false);
  const double limit = 2 * longest_apparent_period(book);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int worst = 0, wrong = 0, undecided = 0;
  for (uint32_t c = 0; c < book.count; ++c) {
    for (int trial = 0; trial < 4; ++trial) {
      Board b{rig.targets[c].markers[0].code.value(), book.bit_period_ns, 400 * u(rng) - 200, 1e9 * u(rng)};
      StreamOptions o;
      o.seed = 100 * c + static_cast<uint64_t>(trial);
      const StreamResult r = run_stream(rig, b, static_cast<int>(c), o);
      wrong += r.wrong;
      if (r.first_decision < 0) {
        ++undecided;
      } else {
        worst = std::max(worst, r.first_decision + 1);
      }
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(undecided, 0);
  EXPECT_LE(worst, limit) << "frames to identify, worst case; two longest periods are " << limit;
  std::printf("[measure] 100 fps, 8 codes, free-running, 10 %% drops: identified within %d frames (two longest apparent "
              "periods: %.0f)\n",
              worst, limit);
}

// With a time base (synchronized boards, phase known) one template per code is
// compared: every code is decided once there are enough samples and, for a slow
// alias, once the camera has seen one of its apparent periods.
TEST(FrequencyIdentifier, WithATimeBaseDecidesAtTheFewestSamples) {
  const protocol::FrequencyCodebook book = codebook_100fps(8);
  const TargetsFile sync = rig_of(book, true);
  const size_t fewest = FrequencyIdentifierOptions{}.min_samples;
  for (uint32_t c = 0; c < book.count; ++c) {
    Board b{sync.targets[c].markers[0].code.value(), book.bit_period_ns, 0, 0};  // locked: board time = rig time
    StreamOptions o;
    o.seed = c;
    o.drop = 0;
    const StreamResult s = run_stream(sync, b, static_cast<int>(c), o);
    EXPECT_EQ(s.wrong, 0);
    const double period = 4294967296.0 / book.codes[c].apparent_q32;
    EXPECT_LE(s.first_decision + 1, std::max(static_cast<double>(fewest) + 2, std::ceil(period))) << "code " << c;
  }
}

// Heavy drops (30 %) and more noise: slower, never wrong.
TEST(FrequencyIdentifier, DroppedFramesAndNoiseNeverMisidentify) {
  const protocol::FrequencyCodebook book = codebook_100fps(8);
  const TargetsFile rig = rig_of(book, false);
  int wrong = 0, undecided = 0;
  for (uint32_t c = 0; c < book.count; ++c) {
    Board b{rig.targets[c].markers[0].code.value(), book.bit_period_ns, -150, 3.3e6 * (c + 1)};
    StreamOptions o;
    o.drop = 0.3;
    o.noise = 0.08;
    o.frames = 160;
    o.seed = 31 + c;
    const StreamResult r = run_stream(rig, b, static_cast<int>(c), o);
    wrong += r.wrong;
    undecided += r.first_decision < 0;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(undecided, 0);
}

// Binary codes (free-running, 15 bits) beside the frequency codes: a binary
// track is never given a frequency code and a frequency track never a binary one.
TEST(FrequencyIdentifier, NeverConfusesBinaryAndFrequencyCodes) {
  const protocol::FrequencyCodebook book = codebook_100fps(6);
  for (ModulationKind kind : {ModulationKind::kOnOff, ModulationKind::kTwoLevel}) {
    TargetsFile rig = rig_of(book, false);
    rig.modulation.kind = kind;
    rig.modulation.low = kind == ModulationKind::kTwoLevel ? 0.3 : 0.0;
    for (const char* text : {"111001110001011", "110110011101001", "010110001100100", "100110101101000"}) {
      Target t;
      t.id = static_cast<int>(rig.targets.size()) + 1;
      for (Marker& m : t.markers) m.code = *parse_code(text, nullptr);
      rig.targets.push_back(t);
    }
    FrequencyIdentifier probe(rig);
    const std::vector<RigCode>& codes = probe.codes();
    ASSERT_EQ(codes.size(), book.count + 4u);
    int wrong = 0, undecided = 0;
    for (size_t c = 0; c < codes.size(); ++c) {
      // Binary codes play on the frequency book's bit period, as one rig shares one time base.
      Board b{codes[c].code, book.bit_period_ns, 120.0 - 40.0 * static_cast<double>(c), 7.7e6 * static_cast<double>(c)};
      b.modulation = kind;
      StreamOptions o;
      o.frames = 120;
      o.seed = 1000 + c;
      const StreamResult r = run_stream(rig, b, static_cast<int>(c), o,
                                        codes[c].frequency ? FrequencyDecision::Kind::kFrequency
                                                           : FrequencyDecision::Kind::kBinary);
      wrong += r.wrong;
      undecided += r.first_decision < 0;
    }
    EXPECT_EQ(wrong, 0) << modulation_name(kind);
    EXPECT_EQ(undecided, 0) << modulation_name(kind);
  }
}

// A constant lamp, and a marker that does not play any of the rig's codes, stay unknown.
TEST(FrequencyIdentifier, ConstantLightAndForeignCodesStayUnknown) {
  const protocol::FrequencyCodebook book = codebook_100fps(8);
  const TargetsFile rig = rig_of(book, false);
  Board lamp{*parse_code("1", nullptr), book.bit_period_ns, 0, 0};
  StreamOptions o;
  o.frames = 120;
  EXPECT_EQ(run_stream(rig, lamp, -1, o).decided_frames, 0);
  // Flicker that is no code of the rig: a random 64-bit word, one bit per frame.
  Board flicker{Code{64, 0x9E3779B97F4A7C15ull}, kFramePeriod, 0, 2.5e6};
  EXPECT_EQ(run_stream(rig, flicker, -1, o).decided_frames, 0);
}

TEST(FrequencyIdentifier, WaitsForEnoughSamplesAndIgnoresBadOnes) {
  const protocol::FrequencyCodebook book = codebook_100fps(4);
  const TargetsFile rig = rig_of(book, false);
  FrequencyIdentifier id(rig);
  id.push(FrequencySample{0, 0, 1.0});                     // no exposure
  id.push(FrequencySample{10, 1000, std::nan("")});        // not a number
  id.push(FrequencySample{20, 1000, 5.0});
  id.push(FrequencySample{10, 1000, 5.0});                 // out of order
  EXPECT_EQ(id.decision().samples, 1u);
  EXPECT_FALSE(id.decision().decided());
  TrackSample coasting;
  coasting.timestamp_ns = 30;
  coasting.exposure_ns = 1000;
  id.push(coasting);  // not detected, not measured: dark
  EXPECT_EQ(id.decision().samples, 2u);
}

}  // namespace
}  // namespace tetrapulse
