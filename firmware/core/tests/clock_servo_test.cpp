// The clock servo on the simulated board: lock time, LED edge accuracy, outliers, holdover.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

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

protocol::Config gpio_config(GpioEdgeNumbering numbering) {
  protocol::Config c = edge_rich_config(1 * kMs);
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

}  // namespace
}  // namespace tetrapulse::fw::testing
