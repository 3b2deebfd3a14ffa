// The virtual rig run by host code over long stretches (label reliability):
//  - sync loss: the trigger line (GPIO board) and the bus (CAN board) disconnected for
//    10 s and restored: each board reports holdover with its length, drifts only by its
//    residual rate error (firmware/README.md: about 0.01 ppm learned, so well under a
//    microsecond here), and relocks; a third board that keeps its sync stays locked; the
//    localizer, fed the camera's frames throughout, poses as many targets through the
//    holdover as before it;
//  - soak: 10 minutes of rig time with boards on GPIO and CAN: every exposure of the
//    trigger accounted for, the synced boards within their servo's bound and never out
//    of lock, every board's LEDs still changing, status answered every second, memory flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "rig_reliability.hpp"

namespace tetrapulse::host::testing {
namespace {

constexpr int64_t kSecond = 1'000'000'000;
constexpr int64_t kMs = 1'000'000;

TEST(SyncLoss, TenSecondsWithoutSyncIsHoldoverThenRelock) {
  sim::Scenario s = mixed_sync_scenario(3);  // GPIO, CAN, GPIO
  const int64_t lost_from = s.frames.start_ns + 5 * kSecond, lost_to = lost_from + 10 * kSecond;
  for (size_t i = 0; i < 2; ++i) s.simulation[i].clock.sync_loss = sim::TimeIntervals({{lost_from, lost_to}});
  auto rig = HostSyncedRig::create(s);
  ASSERT_TRUE(rig) << rig.error().what();
  struct Seen {
    bool holdover = false;
    uint32_t longest_holdover_ms = 0;
    int64_t worst_holdover_error_ns = 0;
    int64_t relocked_after_ns = -1;
    int64_t worst_after_relock_ns = 0;
    uint64_t not_locked = 0;  // the board that keeps its sync
  } seen[3];
  // The camera runs through it all: frame by frame (30 fps), the boards' states read every
  // third frame (100 ms). Poses are counted per 5 s window (15 code cycles of 12 frames):
  // before the loss, its first and last 5 s, and after.
  RigCamera camera(s, *rig);
  const int64_t end = lost_to + 6 * kSecond;
  uint64_t window_poses[4] = {};  // [lost_from - 5 s, lost_from), [lost_from, +5 s), [lost_to - 5 s, lost_to), [lost_to, +5 s)
  const int64_t windows[4] = {lost_from - 5 * kSecond, lost_from, lost_to - 5 * kSecond, lost_to};
  for (int64_t frame = 0;; ++frame) {
    const int64_t t = s.frames.start_ns + frame * s.frames.period_ns;
    if (t >= end) break;
    const auto poses = camera.localize(frame);
    ASSERT_TRUE(poses.has_value()) << "frame " << frame;
    for (int w = 0; w < 4; ++w) {
      if (t >= windows[w] && t < windows[w] + 5 * kSecond) window_poses[w] += poses->size();
    }
    if (frame % 3 != 0 || t < s.frames.start_ns + kSecond) continue;
    (*rig)->run_until(t + s.frames.exposure_ns);
    ASSERT_FALSE((*rig)->failure()) << (*rig)->failure()->what();
    for (size_t i = 0; i < 3; ++i) {
      auto status = (*rig)->host_board(i).status();
      ASSERT_TRUE(status) << status.error().what();
      const int64_t error = std::abs(board_clock_error_ns((*rig)->board(i)));
      Seen& b = seen[i];
      if (i == 2) {
        b.not_locked += status->sync_state != protocol::SyncState::kLocked;
        b.worst_after_relock_ns = std::max(b.worst_after_relock_ns, error);
        continue;
      }
      if (t < lost_from) {
        ASSERT_EQ(status->sync_state, protocol::SyncState::kLocked) << "board " << i << " before the loss";
      } else if (t < lost_to) {
        if (status->sync_state == protocol::SyncState::kHoldover) {
          b.holdover = true;
          b.longest_holdover_ms = std::max(b.longest_holdover_ms, status->holdover_ms);
        }
        b.worst_holdover_error_ns = std::max(b.worst_holdover_error_ns, error);
      } else {
        if (b.relocked_after_ns < 0 && status->sync_state == protocol::SyncState::kLocked) {
          b.relocked_after_ns = t - lost_to;
        }
        if (b.relocked_after_ns >= 0) b.worst_after_relock_ns = std::max(b.worst_after_relock_ns, error);
      }
    }
  }
  std::printf("[measure] sync loss: poses per 5 s: before %llu, first 5 s of holdover %llu, last 5 s %llu, after %llu\n",
              static_cast<unsigned long long>(window_poses[0]), static_cast<unsigned long long>(window_poses[1]),
              static_cast<unsigned long long>(window_poses[2]), static_cast<unsigned long long>(window_poses[3]));
  EXPECT_GT(window_poses[0], 100u);
  for (int w = 1; w < 4; ++w) {
    EXPECT_GE(window_poses[w] * 100, window_poses[0] * 95) << "window " << w << ": the codes still read";
  }
  const char* names[] = {"GPIO", "CAN"};
  for (size_t i = 0; i < 2; ++i) {
    const Seen& b = seen[i];
    std::printf("[measure] sync loss 10 s, %s board: holdover reported %d (up to %u ms), clock error during it"
                " <= %.3f us, relocked %.1f s after sync returned, then within %.3f us\n",
                names[i], b.holdover, b.longest_holdover_ms, b.worst_holdover_error_ns / 1e3,
                b.relocked_after_ns / 1e9, b.worst_after_relock_ns / 1e3);
    EXPECT_TRUE(b.holdover) << names[i];
    EXPECT_GE(b.longest_holdover_ms, 8'000u) << names[i] << ": holdover_ms counts the time without sync";
    // Holdover on the learned rate: about 0.01 ppm (firmware/README.md), 0.1 us in 10 s;
    // the bound leaves room for a CAN board's rate estimate (a few ppb noisier).
    EXPECT_LT(b.worst_holdover_error_ns, i == 0 ? 2'000 : 60'000) << names[i];
    EXPECT_GE(b.relocked_after_ns, 0) << names[i] << " never relocked";
    EXPECT_LT(b.relocked_after_ns, 5 * kSecond) << names[i];
    EXPECT_LT(b.worst_after_relock_ns, i == 0 ? 1'000 : 60'000) << names[i];
  }
  std::printf("[measure] sync loss: the board that kept its sync: %llu reads not locked, within %.1f us\n",
              static_cast<unsigned long long>(seen[2].not_locked), seen[2].worst_after_relock_ns / 1e3);
  EXPECT_EQ(seen[2].not_locked, 0u);
}

TEST(Soak, TenMinutesOfRigTime) {
  const sim::Scenario s = mixed_sync_scenario(4);
  const SoakReport r = soak(s, 600, 60, [](const std::string& line) { std::printf("[soak] %s\n", line.c_str()); });
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::printf("[measure] soak %lld s of rig time: %llu/%llu exposures, %llu CAN syncs, heap in use %ld KiB after 60 s,"
              " %ld KiB at the end (RSS %ld, %ld KiB)\n",
              static_cast<long long>(r.rig_seconds), static_cast<unsigned long long>(r.exposures),
              static_cast<unsigned long long>(r.expected_exposures), static_cast<unsigned long long>(r.can_syncs),
              r.heap_kib_after_warmup, r.heap_kib_end, r.rss_kib_after_warmup, r.rss_kib_end);
  EXPECT_EQ(r.exposures, r.expected_exposures) << "every frame's exposure triggered";
  EXPECT_EQ(r.can_syncs, static_cast<uint64_t>((r.rig_seconds * kSecond + 8 * kSecond - 100 * kMs) / (100 * kMs) + 1))
      << "a Sync every 100 ms from power-up on";
  for (size_t i = 0; i < r.boards.size(); ++i) {
    const SoakBoard& b = r.boards[i];
    std::printf("[measure] soak board %zu (%s): max |clock error| %.3f us, %llu reads not locked, %llu LED changes,"
                " %llu status failures\n",
                i, b.sync == sim::BoardSync::kGpio ? "gpio" : "can",
                b.max_abs_error_ns / 1e3, static_cast<unsigned long long>(b.not_locked),
                static_cast<unsigned long long>(b.led_changes), static_cast<unsigned long long>(b.status_failures));
    EXPECT_EQ(b.status_failures, 0u) << "board " << i;
    EXPECT_GT(b.led_changes, static_cast<uint64_t>(50 * r.rig_seconds)) << "board " << i << " stalled";
    EXPECT_EQ(b.not_locked, 0u) << "board " << i;
    // The servo's bounds (firmware/README.md): GPIO edges within 17 ns, CAN within 20 us
    // in steady state (latency 0..50 us); the clock read here has no input-capture floor.
    EXPECT_LT(b.max_abs_error_ns, b.sync == sim::BoardSync::kGpio ? 1'000 : 50'000) << "board " << i;
  }
  const SoakLocalizer& loc = r.localizer;
  std::printf("[measure] soak localizer: %llu frames in 10 bursts, %llu refused, %llu poses\n",
              static_cast<unsigned long long>(loc.frames), static_cast<unsigned long long>(loc.frame_errors),
              static_cast<unsigned long long>(loc.poses));
  EXPECT_EQ(loc.frames, 600u);
  EXPECT_EQ(loc.frame_errors, 0u);
  ASSERT_EQ(loc.burst_poses.size(), 10u);
  std::string per_burst;
  uint64_t fewest = UINT64_MAX;
  for (uint64_t n : loc.burst_poses) {
    per_burst += " " + std::to_string(n);
    fewest = std::min(fewest, n);
  }
  std::printf("[measure] soak localizer: poses per burst after its first %d frames:%s\n", SoakLocalizer::kSettleFrames,
              per_burst.c_str());
  EXPECT_GT(loc.burst_poses[0], 45u) << "the first burst poses the targets";
  EXPECT_GE(fewest * 10, loc.burst_poses[0] * 9) << "no burst falls below 90 % of the first";
  // With the localizer the heap grows in steps (+0.26 MiB in these 10 minutes, +4.2 MiB in
  // 4 hours): its identifier's hypothesis list keeps the capacity of the largest frame so
  // far, up to max_hypotheses (20000) entries (docs/reliability.md). Reported, not bounded
  // here; the rig alone is bounded below.
  std::printf("[measure] soak: heap in use grew %ld KiB from minute 1 to minute 10 with the localizer\n",
              r.heap_kib_end - r.heap_kib_after_warmup);
}

TEST(Soak, TheRigsMemoryIsFlat) {
  // The same 10 minutes without the camera: boards, sync masters, status reads.
  const SoakReport r = soak(mixed_sync_scenario(4), 600, 0);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::printf("[measure] soak without the localizer: heap in use %ld KiB after 60 s, %ld KiB after 600 s\n",
              r.heap_kib_after_warmup, r.heap_kib_end);
  // A leak of one 16-byte allocation per exposure would be 280 KiB and more.
  EXPECT_LT(r.heap_kib_end - r.heap_kib_after_warmup, 64);
}

}  // namespace
}  // namespace tetrapulse::host::testing
