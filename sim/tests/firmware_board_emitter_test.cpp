// Boards in the loop: the emission of a simulated board running the firmware agrees with
// the contract's formula edge for edge once locked, for GPIO and CAN sync and free-running.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tetrapulse/sim/scenario_yaml.hpp"
#include "tetrapulse/sim/code_emitter.hpp"
#include "tetrapulse/sim/firmware_board_emitter.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace tetrapulse::sim {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

Scenario builtin(const std::string& name) {
  auto s = load_scenario(name);
  EXPECT_TRUE(s) << s.error().what();
  return *s;
}

// Rig times of the level changes the contract formula makes for marker m in [t0, t1).
std::vector<double> contract_edges(const Scenario& s, size_t target, int m, int64_t t0, int64_t t1) {
  const CodeEmitter contract(s.targets.timebase, s.targets.modulation, s.targets.targets[target],
                             BoardClock(s.simulation[target].clock));
  std::vector<double> edges;
  const BoardClockSpec& clock = s.simulation[target].clock;
  const double T = static_cast<double>(s.targets.timebase.bit_period_ns);
  const double epoch = static_cast<double>(s.targets.timebase.epoch_ns);
  const double offset = static_cast<double>(clock.offset_ns);
  // Bit n starts at board time epoch + n T; board time is b = t + offset when locked,
  // b = offset + t (1 + ppm 1e-6) when free-running.
  const double rate = clock.free_running ? 1.0 + clock.drift_ppm * 1e-6 : 1.0;
  const auto rig_of = [&](double b) { return (b - offset) / rate; };
  const auto first = static_cast<int64_t>(std::floor((static_cast<double>(t0) * rate + offset - epoch) / T));
  double before = contract.mean_emission(m, t0 - 2, t0 - 1);
  for (int64_t n = first;; ++n) {
    const double edge = rig_of(epoch + static_cast<double>(n) * T);
    if (edge >= static_cast<double>(t1)) break;
    if (edge < static_cast<double>(t0)) continue;
    const auto at = static_cast<int64_t>(std::ceil(edge));
    const double after = contract.mean_emission(m, at, at + 1);
    if (std::fabs(after - before) > 1e-6) edges.push_back(edge);
    before = after;
  }
  return edges;
}

struct Agreement {
  size_t edges = 0;
  double max_abs_ns = 0;
  double max_emission_diff = 0;  // over exposures, relative emission
};

Agreement compare(const Scenario& s, size_t target, const FirmwareEmitterOptions& options, int64_t seconds) {
  FirmwareBoardEmitter board(s, target, options);
  EXPECT_TRUE(board.configured());
  const CodeEmitter contract(s.targets.timebase, s.targets.modulation, s.targets.targets[target],
                             BoardClock(s.simulation[target].clock));
  const int64_t t0 = s.frames.start_ns, t1 = t0 + seconds * kSecond;
  Agreement a;
  for (int64_t k = 0; s.frames.start_ns + k * s.frames.period_ns < t1; ++k) {
    const int64_t e0 = s.frames.start_ns + k * s.frames.period_ns;
    for (int m = 0; m < 4; ++m) {
      const double d = std::fabs(board.mean_emission(m, e0, e0 + s.frames.exposure_ns) -
                                 contract.mean_emission(m, e0, e0 + s.frames.exposure_ns));
      a.max_emission_diff = std::max(a.max_emission_diff, d);
    }
  }
  board.run_until(t1);
  for (int m = 0; m < 4; ++m) {
    const std::vector<double> want = contract_edges(s, target, m, t0, t1);
    std::vector<double> got;
    for (const sim_board::AppliedLedChange& c : board.board().leds().log(static_cast<uint8_t>(m))) {
      if (c.rig_ns >= t0 && c.rig_ns < t1) got.push_back(static_cast<double>(c.rig_ns));
    }
    EXPECT_EQ(got.size(), want.size()) << "marker " << m;
    for (size_t i = 0; i < std::min(got.size(), want.size()); ++i) {
      a.max_abs_ns = std::max(a.max_abs_ns, std::fabs(got[i] - want[i]));
    }
    a.edges += want.size();
  }
  return a;
}

TEST(FirmwareBoardEmitter, AgreesWithTheContractEdgeForEdgeUnderGpioSync) {
  Scenario s = builtin("paper-exp1");
  s.simulation[0].clock.drift_ppm = 87;  // a poor crystal; the servo takes it out
  s.simulation[0].clock.offset_ns = 0;
  const Agreement a = compare(s, 0, FirmwareEmitterOptions{}, 5);
  std::printf("[measure] board emitter vs contract, gpio sync, +87 ppm: %zu edges, max |dt| %.1f ns, max emission diff %.2e\n",
              a.edges, a.max_abs_ns, a.max_emission_diff);
  EXPECT_GT(a.edges, 500u);
  EXPECT_LT(a.max_abs_ns, 1000.0);
  // An edge 1 us off changes a 2 ms exposure's mean by at most 1/2000.
  EXPECT_LT(a.max_emission_diff, 5e-4);
}

TEST(FirmwareBoardEmitter, AgreesWithinCanSyncAccuracyUnderCanSync) {
  Scenario s = builtin("paper-exp1");
  s.simulation[0].clock.drift_ppm = -64;
  s.simulation[0].clock.sync = BoardSync::kCan;
  const Agreement a = compare(s, 0, FirmwareEmitterOptions{}, 5);
  std::printf("[measure] board emitter vs contract, can sync, -64 ppm: %zu edges, max |dt| %.1f us, max emission diff %.2e\n",
              a.edges, a.max_abs_ns / 1e3, a.max_emission_diff);
  EXPECT_GT(a.edges, 500u);
  EXPECT_LT(a.max_abs_ns, 20'000.0);
}

TEST(FirmwareBoardEmitter, FreeRunningBoardPlaysTheContractsDriftingClock) {
  Scenario s = builtin("unsync");
  ASSERT_TRUE(s.simulation[0].clock.free_running);
  ASSERT_EQ(s.simulation[0].clock.sync, BoardSync::kNone);
  const Agreement a = compare(s, 0, FirmwareEmitterOptions{}, 3);
  std::printf("[measure] board emitter vs contract, free-running %+.1f ppm offset %lld ns: %zu edges, max |dt| %.1f ns\n",
              s.simulation[0].clock.drift_ppm, static_cast<long long>(s.simulation[0].clock.offset_ns), a.edges,
              a.max_abs_ns);
  EXPECT_GT(a.edges, 100u);
  EXPECT_LT(a.max_abs_ns, 1000.0);
}

// Frequency codes of different lengths on one board (the `frequency` scenario's target 4:
// 39, 44, 47 and 60 bits on its four markers, free-running at -120 ppm) and one length on
// all markers (target 1, +180 ppm): the firmware plays the contract's edges.
TEST(FirmwareBoardEmitter, PlaysFrequencyCodesOfDifferentLengthsPerMarker) {
  const Scenario s = builtin("frequency");
  for (size_t target : {size_t{3}, size_t{0}}) {
    const Agreement a = compare(s, target, FirmwareEmitterOptions{}, 2);
    std::printf("[measure] board emitter vs contract, frequency codes, target %zu: %zu edges, max |dt| %.1f ns\n",
                target, a.edges, a.max_abs_ns);
    EXPECT_GT(a.edges, 1000u);
    EXPECT_LT(a.max_abs_ns, 1000.0);
    EXPECT_LT(a.max_emission_diff, 2e-3);
  }
}

TEST(FirmwareBoardEmitter, IsTheDefaultWhenTheFirmwareIsBuilt) {
  const Scenario s = builtin("paper-exp1");
  const auto emitter = default_board_emitter()(s, 0);
  EXPECT_NE(dynamic_cast<const FirmwareBoardEmitter*>(emitter.get()), nullptr);
}

}  // namespace
}  // namespace tetrapulse::sim

namespace tetrapulse::sim {
namespace {

// Sync loss (clutter: the line is lost for 0.25 s and 10 s): the board holds over on its
// learned rate, then numbers the returning edges right and locks again.
TEST(FirmwareBoardEmitter, HoldsOverThroughSyncLossAndRelocks) {
  Scenario s = builtin("clutter");
  s.simulation[0].clock.offset_ns = 0;
  FirmwareBoardEmitter board(s, 0);
  ASSERT_TRUE(board.configured());
  board.run_until(s.frames.start_ns + 17 * kSecond);
  const auto worst = [&](int64_t t0, int64_t t1) {
    double w = 0;
    for (int m = 0; m < 4; ++m) {
      for (const sim_board::AppliedLedChange& c : board.board().leds().log(static_cast<uint8_t>(m))) {
        if (c.rig_ns < t0 || c.rig_ns >= t1) continue;
        const double T = static_cast<double>(s.targets.timebase.bit_period_ns);
        const double rel = static_cast<double>(c.rig_ns) - static_cast<double>(s.targets.timebase.epoch_ns);
        w = std::max(w, std::fabs(rel - std::round(rel / T) * T));
      }
    }
    return w;
  };
  const double during = worst(5 * kSecond, 15 * kSecond);
  const double after = worst(16 * kSecond, 17 * kSecond);
  std::printf("[measure] clutter sync loss 10 s at %+.0f ppm: worst edge error during %.2f us, 1 s after return %.1f ns\n",
              s.simulation[0].clock.drift_ppm, during / 1e3, after);
  EXPECT_LT(during, 20'000.0);
  EXPECT_LT(after, 1'000.0);
  EXPECT_EQ(board.board().status().sync_state, protocol::SyncState::kLocked);
}

}  // namespace
}  // namespace tetrapulse::sim
