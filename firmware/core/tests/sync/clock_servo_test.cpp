// The clock servo on the simulated board: lock time, LED edge accuracy, outliers, holdover.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include "board_testing.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::GpioEdgeNumbering;
using protocol::SyncSource;
using protocol::SyncState;

constexpr int64_t kEdgePeriod = 10 * kMs;  // 100 Hz camera

sim_board::SimBoardOptions board_at(double ppm, int64_t power_on_ns = 0) {
  sim_board::SimBoardOptions o;
  o.clock_ppm = ppm;
  o.power_on_ns = power_on_ns;
  return o;
}

protocol::Config gpio_config(GpioEdgeNumbering numbering, uint32_t bit_period_ns = 1 * kMs) {
  protocol::Config c = edge_rich_config(bit_period_ns);
  c.sync_source = SyncSource::kGpio;
  c.gpio_edge_period_ns = kEdgePeriod;
  c.gpio_edge_epoch_ns = 0;
  c.gpio_edge_numbering = numbering;
  return c;
}

// Runs GPIO edges every kEdgePeriod from `from` to `to` (rig ns); FollowUps on USB every
// second give coarse time. Returns the rig time the board first reported locked (or -1).
int64_t run_gpio(TestBoard& b, int64_t from, int64_t to, int64_t skip_edge_at = -1, int64_t extra_edge_at = -1) {
  int64_t locked_at = -1;
  uint16_t seq = 0;
  for (int64_t t = from; t < to; t += kEdgePeriod) {
    if (t % kSecond == 0) {
      // The host's coarse time, a little late (USB latency 300 us).
      b.host.send(LinkKind::kUsb, protocol::Message{0, protocol::FollowUp{seq++, t}}, t + 300'000);
    }
    if (t != skip_edge_at) b.board.sync_edge(t);
    if (extra_edge_at >= t && extra_edge_at < t + kEdgePeriod) b.board.sync_edge(extra_edge_at);
    if (locked_at < 0 && b.sync_state() == SyncState::kLocked) locked_at = t;
  }
  b.board.advance_to(to);
  return locked_at;
}

class GpioLock : public ::testing::TestWithParam<std::tuple<double, GpioEdgeNumbering>> {};

TEST_P(GpioLock, LocksWithin2sAt100ppmAndEdgesWithin1us) {
  const auto [ppm, numbering] = GetParam();
  // Power on at an odd time, so the counter's zero is nowhere near an edge.
  TestBoard b(board_at(ppm, 123'456'789));
  const int64_t start = 2 * kSecond;
  b.board.advance_to(start - 500 * kMs);  // sync input enabled well before the first edge
  b.configure(gpio_config(numbering));
  const int64_t locked_at = run_gpio(b, start, start + 6 * kSecond);
  ASSERT_GE(locked_at, 0) << "never locked";
  const double lock_s = static_cast<double>(locked_at - start) / 1e9;
  const EdgeTiming timing = edge_timing(b.board, protocol::TimeBase{0, 1 * kMs}, locked_at, start + 6 * kSecond);
  std::printf("[measure] gpio %+.0f ppm numbering %d: lock %.3f s, edges %zu, max |err| %.1f ns, mean %.1f ns, rms %.1f ns\n",
              ppm, static_cast<int>(numbering), lock_s, timing.count, timing.max_abs_ns, timing.mean_ns, timing.rms_ns);
  EXPECT_LT(lock_s, 2.0);
  EXPECT_GT(timing.count, 10000u);
  EXPECT_LT(timing.max_abs_ns, 1000.0);
  const protocol::StatusReport s = b.board.status();
  EXPECT_EQ(s.sync_state, SyncState::kLocked);
  EXPECT_NEAR(s.rate_ppb, ppm * 1000, 100);
}

INSTANTIATE_TEST_SUITE_P(ClockServo, GpioLock,
                         ::testing::Combine(::testing::Values(-100.0, -37.0, 0.0, 61.0, 100.0),
                                            ::testing::Values(GpioEdgeNumbering::kNearestCoarseTime,
                                                              GpioEdgeNumbering::kCountAfterGap)));

}  // namespace
}  // namespace tetrapulse::fw::testing

namespace tetrapulse::fw::testing {
namespace {

struct CanRun {
  int64_t locked_at = -1;
};

// Sync/FollowUp over CAN at `rate_hz` from `from` to `to`; each Sync reaches the board
// `jitter` later (uniform in [0, jitter_ns]: interrupt latency, arbitration), its FollowUp
// 1 ms after the Sync.
CanRun run_can(TestBoard& b, int64_t from, int64_t to, int64_t period_ns, int64_t jitter_ns, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int64_t> jitter(0, jitter_ns);
  CanRun run;
  uint16_t seq = 0;
  for (int64_t t = from; t < to; t += period_ns) {
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{seq}}, t + jitter(rng));
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{seq, t}}, t + kMs);
    ++seq;
    if (run.locked_at < 0 && b.sync_state() == SyncState::kLocked) run.locked_at = t;
  }
  b.board.advance_to(to);
  return run;
}

protocol::Config can_config() {
  protocol::Config c = edge_rich_config(1 * kMs);
  c.sync_source = SyncSource::kCan;
  return c;
}

class CanLock : public ::testing::TestWithParam<double> {};

TEST_P(CanLock, LocksWithin5sAt100ppmWith50usJitter) {
  const double ppm = GetParam();
  TestBoard b(board_at(ppm, 77'000'001));
  const int64_t start = 1 * kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_config());
  const int64_t end = start + 40 * kSecond;
  const CanRun run = run_can(b, start, end, 100 * kMs, 50'000, 7);
  ASSERT_GE(run.locked_at, 0) << "never locked";
  const double lock_s = static_cast<double>(run.locked_at - start) / 1e9;
  const protocol::TimeBase tb{0, 1 * kMs};
  const EdgeTiming after_lock = edge_timing(b.board, tb, run.locked_at, end);
  const EdgeTiming steady = edge_timing(b.board, tb, start + 20 * kSecond, end);
  std::printf("[measure] can %+.0f ppm, 10 Hz, jitter 0..50 us: lock %.2f s; after lock max |err| %.1f us;"
              " steady (20-40 s) mean %.1f us, rms %.1f us, max |err| %.1f us\n",
              ppm, lock_s, after_lock.max_abs_ns / 1e3, steady.mean_ns / 1e3, steady.rms_ns / 1e3,
              steady.max_abs_ns / 1e3);
  EXPECT_LT(lock_s, 5.0);
  EXPECT_LT(steady.max_abs_ns, 20'000.0);
  EXPECT_EQ(b.sync_state(), SyncState::kLocked);
}

INSTANTIATE_TEST_SUITE_P(ClockServo, CanLock, ::testing::Values(-100.0, -20.0, 0.0, 45.0, 100.0));

// A loaded receiver (an emulated machine, a busy host): most Syncs arrive within 50 us, one
// in five 150..400 us late, the first one among them. Acquisition takes the earliest
// arrivals, not the first samples, so the board locks close to rig time and stays locked.
class CanLateSpikes : public ::testing::TestWithParam<uint32_t> {};

TEST_P(CanLateSpikes, LocksWithin200usAndStaysLocked) {
  const uint32_t seed = GetParam();
  TestBoard b(board_at(40, 7'000'000 + seed));
  const int64_t start = 1 * kSecond, end = start + 30 * kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_config());
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int64_t> jitter(0, 50'000), spike(150'000, 400'000);
  std::uniform_int_distribution<int> one_in(0, 4);
  int64_t locked_at = -1;
  int unlocked_after_lock = 0;
  uint16_t seq = 0;
  for (int64_t t = start; t < end; t += 100 * kMs, ++seq) {
    const int64_t late = t == start || one_in(rng) == 0 ? spike(rng) : jitter(rng);
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{seq}}, t + late);
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{seq, t}}, t + late + kMs);
    const bool locked = b.sync_state() == SyncState::kLocked;
    if (locked_at < 0 && locked) locked_at = t;
    if (locked_at >= 0 && !locked) ++unlocked_after_lock;
  }
  b.board.advance_to(end);
  ASSERT_GE(locked_at, 0) << "never locked";
  const EdgeTiming after = edge_timing(b.board, protocol::TimeBase{0, kMs}, locked_at, end);
  std::printf("[measure] can with 1 in 5 Syncs 150..400 us late (seed %u): lock %.1f s, after lock max |err| %.1f us,"
              " %d samples not locked\n",
              seed, static_cast<double>(locked_at - start) / 1e9, after.max_abs_ns / 1e3, unlocked_after_lock);
  EXPECT_LT(after.max_abs_ns, 200'000.0);
  EXPECT_EQ(unlocked_after_lock, 0);
}

INSTANTIATE_TEST_SUITE_P(ClockServo, CanLateSpikes, ::testing::Range(1u, 9u));

// The VM's flake (vm.board.can under TCG): locked, one sample 150..400 us off, at random
// points. A late Sync costs nothing (the minimum-latency filter takes the earliest
// arrival); one whose FollowUp time is that much later than its reception (a tx stamp or
// clock conversion off by a preemption) looks early, led the filter for its 16 samples and
// swung the rate to -170..-500 ppm, 250 us off and unlocked, as in the VM. Locked, such a
// sample is held out.
enum class Spike { kLateSync, kLateStamp };

class CanSingleSpikes : public ::testing::TestWithParam<std::tuple<uint32_t, Spike>> {};

struct SpikeRun {
  int64_t locked_at = -1;
  int unlocked_after_lock = 0;
  int spikes = 0;
  std::vector<int32_t> rate_ppb;  // after every FollowUp
  EdgeTiming after_lock;
};

// 40 s of 10 Hz Sync/FollowUp with 0..50 us latency; with `spikes`, from lock on, one
// sample every 1..4 s is 150..400 us off (its own generator: the jitter is the same with
// and without).
SpikeRun run_spikes(uint32_t seed, Spike kind, bool spikes) {
  TestBoard b(board_at(40, 9'000'000 + seed));
  const int64_t start = 1 * kSecond, end = start + 40 * kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_config());
  std::mt19937 rng(seed), spike_rng(seed + 1000);
  std::uniform_int_distribution<int64_t> jitter(0, 50'000), spike(150'000, 400'000);
  std::uniform_int_distribution<int> gap(10, 40);
  SpikeRun run;
  int next_spike = -1;
  uint16_t seq = 0;
  for (int64_t t = start; t < end; t += 100 * kMs, ++seq) {
    int64_t rx = t + jitter(rng), stamp = t;
    if (spikes && run.locked_at >= 0 && next_spike < 0) next_spike = seq + gap(spike_rng);
    if (seq == next_spike) {
      (kind == Spike::kLateSync ? rx : stamp) += spike(spike_rng);
      next_spike = -1;
      ++run.spikes;
    }
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{seq}}, rx);
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{seq, stamp}}, rx + kMs);
    const protocol::StatusReport s = b.board.status();
    const bool locked = s.sync_state == SyncState::kLocked;
    if (run.locked_at < 0 && locked) run.locked_at = t;
    if (run.locked_at >= 0 && !locked) ++run.unlocked_after_lock;
    run.rate_ppb.push_back(s.rate_ppb);
  }
  b.board.advance_to(end);
  if (run.locked_at >= 0) run.after_lock = edge_timing(b.board, protocol::TimeBase{0, kMs}, run.locked_at, end);
  return run;
}

TEST_P(CanSingleSpikes, OneSampleOffWhileLockedMovesNothing) {
  const auto [seed, kind] = GetParam();
  const SpikeRun clean = run_spikes(seed, kind, false);
  const SpikeRun spiky = run_spikes(seed, kind, true);
  ASSERT_GE(spiky.locked_at, 0) << "never locked";
  ASSERT_EQ(spiky.rate_ppb.size(), clean.rate_ppb.size());
  int32_t rate_moved_ppb = 0;
  for (size_t i = 0; i < spiky.rate_ppb.size(); ++i) {
    rate_moved_ppb = std::max(rate_moved_ppb, std::abs(spiky.rate_ppb[i] - clean.rate_ppb[i]));
  }
  std::printf("[measure] can locked, %d single %s 150..400 us (seed %u): after lock max |err| %.1f us (%.1f without),"
              " rate moved by at most %.2f ppm, %d samples not locked\n",
              spiky.spikes, kind == Spike::kLateSync ? "late Syncs" : "late stamps", seed,
              spiky.after_lock.max_abs_ns / 1e3, clean.after_lock.max_abs_ns / 1e3, rate_moved_ppb / 1e3,
              spiky.unlocked_after_lock);
  EXPECT_GE(spiky.spikes, 8);
  EXPECT_EQ(spiky.unlocked_after_lock, 0);
  EXPECT_LT(spiky.after_lock.max_abs_ns, 50'000.0) << "within the steady state's bound (worst measured 36 us)";
  EXPECT_LT(rate_moved_ppb, 5'000) << "a spike moves the rate by less than 5 ppm (before: 170..500 ppm)";
}

INSTANTIATE_TEST_SUITE_P(ClockServo, CanSingleSpikes,
                         ::testing::Combine(::testing::Range(1u, 17u), ::testing::Values(Spike::kLateSync, Spike::kLateStamp)));

// A real step of the time base by +150 us (inside the locked outlier gate): the first
// samples are held out, the run of unlock_count of them unlocks the servo, which follows
// and locks again at the new time.
TEST(ClockServo, FollowsARealStepAfterARunOfHeldOutSamples) {
  TestBoard b(board_at(40, 9'500'000));
  const int64_t start = 1 * kSecond, step_at = start + 15 * kSecond, end = start + 40 * kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_config());
  std::mt19937 rng(3);
  std::uniform_int_distribution<int64_t> jitter(0, 50'000);
  constexpr int64_t kStep = 150'000;
  bool unlocked = false;
  int64_t relocked_at = -1;
  uint16_t seq = 0;
  for (int64_t t = start; t < end; t += 100 * kMs, ++seq) {
    const int64_t rx = t + jitter(rng) - (t >= step_at ? kStep : 0);
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{seq}}, rx);
    b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{seq, t}}, rx + kMs);
    const bool locked = b.sync_state() == SyncState::kLocked;
    if (t == step_at - 100 * kMs) {
      ASSERT_TRUE(locked) << "locked before the step";
    }
    if (t >= step_at && !locked) unlocked = true;
    if (unlocked && locked && relocked_at < 0) relocked_at = t;
  }
  b.board.advance_to(end);
  const protocol::StatusReport s = b.board.status();
  // The board's rig time now runs kStep ahead of the true rig time the LED log records:
  // its bit edges fall kStep early.
  const EdgeTiming settled = edge_timing(b.board, protocol::TimeBase{kMs - kStep, kMs}, end - 10 * kSecond, end);
  std::printf("[measure] can step +150 us while locked: unlocked %d, locked again %.1f s after the step, then max"
              " |err| %.1f us\n",
              unlocked, static_cast<double>(relocked_at - step_at) / 1e9, settled.max_abs_ns / 1e3);
  EXPECT_TRUE(unlocked) << "a step is not held out for ever";
  EXPECT_GE(relocked_at, 0);
  EXPECT_EQ(s.sync_state, SyncState::kLocked);
  EXPECT_LT(settled.max_abs_ns, 50'000.0);
}

// The lock state's hysteresis on the servo alone, with the loop gains at zero so that an
// offset stays exactly what it is fed: a 1 GHz counter (a tick is a nanosecond), samples
// every 10 ms, locked below 100 ns, unlocked after 3 samples in a row above 400 ns.
TEST(ClockServo, LeavesLockOnlyAfterUnlockCountSamplesFarOff) {
  ServoTuning tuning;
  tuning.kp_256 = 0;
  tuning.ki_256 = 0;
  tuning.lock_threshold_ns = 100;
  tuning.lock_count = 4;
  tuning.unlock_count = 3;
  tuning.gate_locked_ns = 10'000;
  ClockServo servo(1'000'000'000);
  servo.restart(tuning);
  int64_t t = 0;
  const auto feed = [&](int64_t offset_ns) {
    t += 10 * kMs;
    servo.add_sample(static_cast<Tick>(t), t + offset_ns);
    return servo.state(static_cast<Tick>(t));
  };
  for (int i = 0; i < 6; ++i) feed(0);
  ASSERT_EQ(servo.state(static_cast<Tick>(t)), SyncState::kLocked);
  EXPECT_EQ(feed(500), SyncState::kLocked);
  EXPECT_EQ(feed(500), SyncState::kLocked) << "two samples far off are a burst, not a lost lock";
  EXPECT_EQ(feed(0), SyncState::kLocked);
  EXPECT_EQ(feed(500), SyncState::kLocked);
  EXPECT_EQ(feed(-500), SyncState::kLocked);
  EXPECT_EQ(feed(500), SyncState::kAcquiring) << "three in a row, either sign: unlocked";
  for (int i = 0; i < 3; ++i) EXPECT_EQ(feed(0), SyncState::kAcquiring);
  EXPECT_EQ(feed(0), SyncState::kLocked) << "lock_count good samples lock again";
}

}  // namespace
}  // namespace tetrapulse::fw::testing

namespace tetrapulse::fw::testing {
namespace {

// Largest shift of any LED change of any marker in [from, to) between two runs that
// should have played the same edges.
double max_shift_ns(const sim_board::SimBoard& a, const sim_board::SimBoard& b, int64_t from, int64_t to) {
  double worst = 0;
  for (uint8_t m = 0; m < kLedCount; ++m) {
    const std::vector<long double> ta = change_times(a, m, from, to);
    const std::vector<long double> tb = change_times(b, m, from, to);
    if (ta.size() != tb.size()) return 1e18;  // an edge appeared or vanished
    for (size_t i = 0; i < ta.size(); ++i) worst = std::max(worst, static_cast<double>(std::fabs(ta[i] - tb[i])));
  }
  return worst;
}

struct Disturbance {
  const char* name;
  int64_t skip_edge_at;   // -1: none
  int64_t extra_edge_at;  // -1: none
};

class GpioOutlier : public ::testing::TestWithParam<std::tuple<Disturbance, GpioEdgeNumbering>> {};

TEST_P(GpioOutlier, MovesNoLedEdgeBeyond5us) {
  const auto [d, numbering] = GetParam();
  const int64_t start = 1 * kSecond, end = start + 5 * kSecond;
  TestBoard clean(board_at(100, 3'000'000));
  TestBoard hit(board_at(100, 3'000'000));
  for (TestBoard* b : {&clean, &hit}) {
    b->board.advance_to(start - 300 * kMs);
    b->configure(gpio_config(numbering));
  }
  run_gpio(clean, start, end);
  run_gpio(hit, start, end, d.skip_edge_at, d.extra_edge_at);
  const double shift = max_shift_ns(clean.board, hit.board, start + 2 * kSecond, end);
  std::printf("[measure] gpio outlier %s (numbering %d): largest LED edge shift %.1f ns, state %d\n", d.name,
              static_cast<int>(numbering), shift, static_cast<int>(hit.sync_state()));
  EXPECT_LT(shift, 5'000.0);
  EXPECT_EQ(hit.sync_state(), SyncState::kLocked);
}

constexpr int64_t kHitAt = 3 * kSecond;  // well after lock
INSTANTIATE_TEST_SUITE_P(
    ClockServo, GpioOutlier,
    ::testing::Combine(::testing::Values(Disturbance{"missed edge", kHitAt, -1},
                                         Disturbance{"doubled edge +3us", -1, kHitAt + 3'000},
                                         Disturbance{"bounce +40us", -1, kHitAt + 40'000},
                                         Disturbance{"spurious mid-period", -1, kHitAt + 5 * kMs},
                                         Disturbance{"glitch 2us early", -1, kHitAt - 2'000},
                                         Disturbance{"missed and doubled", kHitAt, kHitAt + 10 * kMs + 1'000}),
                       ::testing::Values(GpioEdgeNumbering::kNearestCoarseTime, GpioEdgeNumbering::kCountAfterGap)));

TEST(ClockServo, StaleOrUnpairedFollowUpNeverJumpsTheClock) {
  const int64_t start = 1 * kSecond, end = start + 20 * kSecond;
  TestBoard b(board_at(-80, 5'000'000));
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_config());
  run_can(b, start, start + 10 * kSecond, 100 * kMs, 50'000, 3);
  const uint32_t rejected_before = b.board.status().sync_rejected;
  const EdgeTiming before = edge_timing(b.board, protocol::TimeBase{0, kMs}, start + 8 * kSecond, start + 10 * kSecond);
  // A FollowUp whose Sync was lost, a FollowUp repeated (stale), one for an old seq with a
  // time 5 ms off, and a Sync/FollowUp pair whose tx time is 3 ms wrong (a master glitch).
  const int64_t t = start + 10 * kSecond;
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{900, t}}, t + kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{901}}, t + 20 * kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{901, t + 20 * kMs}}, t + 21 * kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{901, t + 25 * kMs}}, t + 22 * kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{700, t + 30 * kMs}}, t + 31 * kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::Sync{902}}, t + 50 * kMs);
  b.host.send(LinkKind::kCan, protocol::Message{0, protocol::FollowUp{902, t + 53 * kMs}}, t + 51 * kMs);
  run_can(b, t + 100 * kMs, end, 100 * kMs, 50'000, 4);
  const EdgeTiming after = edge_timing(b.board, protocol::TimeBase{0, kMs}, t, end);
  const protocol::StatusReport s = b.board.status();
  std::printf("[measure] can stale/unpaired FollowUps: max |err| before %.1f us, after %.1f us; rejected %u -> %u\n",
              before.max_abs_ns / 1e3, after.max_abs_ns / 1e3, rejected_before, s.sync_rejected);
  EXPECT_LT(after.max_abs_ns, 20'000.0);
  EXPECT_GE(s.sync_rejected, rejected_before + 4);
  EXPECT_EQ(s.sync_state, SyncState::kLocked);
}

// Holdover: locked on GPIO, then no more edges. Mean LED edge error in a 100 ms window
// 1, 10 and 60 s after the last edge, with the crystal as it was and with it moved by a
// few ppm (temperature) when sync stopped.
class Holdover : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(Holdover, DriftsOnlyByTheResidualRate) {
  const auto [ppm, residual_ppm] = GetParam();
  TestBoard b(board_at(ppm, 1'000'000));
  const int64_t start = kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(gpio_config(GpioEdgeNumbering::kCountAfterGap, 10 * kMs));
  const int64_t last = start + 5 * kSecond;
  run_gpio(b, start, last + kEdgePeriod);
  const int64_t stop = last + kEdgePeriod;
  if (residual_ppm != 0) b.board.set_clock_ppm(ppm + residual_ppm);
  double at[3] = {0, 0, 0};
  const int64_t marks[3] = {1 * kSecond, 10 * kSecond, 60 * kSecond};
  for (int i = 0; i < 3; ++i) {
    b.board.advance_to(last + marks[i] + 100 * kMs);
    at[i] = edge_timing(b.board, protocol::TimeBase{0, 10 * kMs}, last + marks[i], last + marks[i] + 100 * kMs).mean_ns;
  }
  const protocol::StatusReport s = b.board.status();
  std::printf("[measure] holdover %+.0f ppm crystal, %+.1f ppm change: error after 1 s %.3f us, 10 s %.3f us, 60 s %.3f us;"
              " state %d holdover_ms %u\n",
              ppm, residual_ppm, at[0] / 1e3, at[1] / 1e3, at[2] / 1e3, static_cast<int>(s.sync_state), s.holdover_ms);
  EXPECT_EQ(s.sync_state, SyncState::kHoldover);
  EXPECT_NEAR(static_cast<double>(s.holdover_ms), static_cast<double>(b.board.now() - stop) / 1e6, 50.0);
  // The rate learned while locked is good to well under 0.1 ppm: the drift is what the
  // crystal changed by, times the time without sync (plus that small residue).
  for (int i = 0; i < 3; ++i) {
    const double expected = -residual_ppm * 1e-6 * static_cast<double>(marks[i]);
    EXPECT_NEAR(at[i], expected, 100.0 + 0.1e-6 * static_cast<double>(marks[i])) << "after " << marks[i] / kSecond << " s";
  }
}

INSTANTIATE_TEST_SUITE_P(ClockServo, Holdover,
                         ::testing::Values(std::make_tuple(100.0, 0.0), std::make_tuple(-100.0, 0.0),
                                           std::make_tuple(100.0, 2.0), std::make_tuple(100.0, -5.0)));

}  // namespace
}  // namespace tetrapulse::fw::testing

namespace tetrapulse::fw::testing {
namespace {

// Sync returns after holdover with the crystal moved: the board is locked again and its
// edges are back within 1 us shortly after.
TEST(ClockServo, RelocksAfterHoldoverWhenSyncReturns) {
  for (const int64_t silence_s : {2, 10, 60}) {
    TestBoard b(board_at(90, 2'000'000));
    b.board.advance_to(kSecond - 100 * kMs);
    b.configure(gpio_config(GpioEdgeNumbering::kNearestCoarseTime, 10 * kMs));
    const int64_t stop = 4 * kSecond;
    run_gpio(b, kSecond, stop);
    b.board.set_clock_ppm(90 - 4);  // 4 ppm of temperature drift while sync is away
    const int64_t back = stop + silence_s * kSecond;
    b.board.advance_to(back);
    EXPECT_EQ(b.sync_state(), SyncState::kHoldover);
    const int64_t relocked = run_gpio(b, back, back + 3 * kSecond);
    ASSERT_GE(relocked, 0) << silence_s << " s";
    const EdgeTiming after = edge_timing(b.board, protocol::TimeBase{0, 10 * kMs}, relocked + 500 * kMs, back + 3 * kSecond);
    std::printf("[measure] sync back after %lld s of holdover (4 ppm drift): locked again after %.2f s, then max |err| %.1f ns\n",
                static_cast<long long>(silence_s), static_cast<double>(relocked - back) / 1e9, after.max_abs_ns);
    EXPECT_LT(relocked - back, kSecond);
    EXPECT_LT(after.max_abs_ns, 1000.0);
  }
}

}  // namespace
}  // namespace tetrapulse::fw::testing
