// The sync master's logic without hardware (tests/vm/host runs it on vcan and gpio-sim):
// CanSync's Sync/FollowUp pairs and their transmit-time sources over an in-memory bus, the
// strobe edge pairing, and the exposures file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "can_board_responder.hpp"
#include "fake_can_bus.hpp"
#include "tetrapulse/host/can_sync.hpp"
#include "tetrapulse/host/exposure.hpp"

namespace tetrapulse::host {
namespace {

using testing::CanBoardResponder;
using testing::FakeCanBus;

struct SyncRig {
  FakeCanBus bus;
  CanBoardResponder board;
  explicit SyncRig() {
    bus.attach([this](const protocol::CanFrame& f, int64_t t) { return board.on_frame(f, t); });
  }
  std::unique_ptr<CanSync> sync(bool tx_stamps, bool echo, RigClock clock = RigClock()) {
    SocketCanOptions o;
    o.tx_timestamps = tx_stamps;
    o.receive_own = echo;
    CanSyncOptions s;
    s.period_ns = 5'000'000;
    s.stamp_wait = std::chrono::milliseconds(5);
    return std::make_unique<CanSync>(bus.open(o), clock, s);
  }
};

TEST(CanSync, FollowUpCarriesTheKernelTransmitTimeOfItsSyncInRigTime) {
  SyncRig rig;
  const RigClock clock(5'000'000'000);  // rig time runs 5 s ahead of CLOCK_MONOTONIC
  auto sync = rig.sync(true, true, clock);
  std::vector<CanSyncSample> samples;
  for (int i = 0; i < 3; ++i) {
    auto s = sync->send_one();
    ASSERT_TRUE(s) << s.error().what();
    EXPECT_EQ(s->source, TxStampSource::kKernelTransmit);
    samples.push_back(*s);
  }
  const auto& seen = rig.board.responder().sync_samples();
  ASSERT_EQ(seen.size(), 3u) << "every FollowUp paired with its Sync at the board";
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(seen[i].sync_seq, i);
    EXPECT_EQ(seen[i].tx_time_ns, samples[i].tx_time_ns);
    // The board stamps reception on CLOCK_MONOTONIC here: the FollowUp is in rig time, 5 s on.
    EXPECT_NEAR(static_cast<double>(seen[i].tx_time_ns - seen[i].received_ns), 5e9, 1e9);
  }
  // Sync (single frame) then FollowUp (3 frames), priority 0, broadcast from the host.
  ASSERT_EQ(rig.bus.frames().size(), 12u);
  EXPECT_EQ(rig.bus.frames()[0].id, 0x0040FF00u);
  EXPECT_EQ(rig.bus.frames()[1].id, 0x0041FF00u);
}

TEST(CanSync, FallsBackToTheOwnEchoThenToTheSendCall) {
  {
    SyncRig rig;
    auto sync = rig.sync(false, true);
    auto s = sync->send_one();
    ASSERT_TRUE(s) << s.error().what();
    EXPECT_EQ(s->source, TxStampSource::kOwnEcho);
  }
  SyncRig rig;
  auto sync = rig.sync(false, false);
  auto s = sync->send_one();
  ASSERT_TRUE(s) << s.error().what();
  EXPECT_EQ(s->source, TxStampSource::kSendCall);
  EXPECT_EQ(rig.board.responder().sync_samples().size(), 1u);
}

TEST(CanSync, RunSendsAtTheConfiguredRateUntilTheCount) {
  SyncRig rig;
  auto sync = rig.sync(true, false);
  std::atomic<bool> stop{false};
  std::vector<CanSyncSample> samples;
  auto sent = sync->run(stop, 4, [&](const CanSyncSample& s) { samples.push_back(s); });
  ASSERT_TRUE(sent) << sent.error().what();
  EXPECT_EQ(*sent, 4u);
  ASSERT_EQ(samples.size(), 4u);
  for (size_t i = 1; i < samples.size(); ++i) {
    EXPECT_EQ(samples[i].sync_seq, samples[i - 1].sync_seq + 1);
    EXPECT_GE(samples[i].tx_time_ns - samples[i - 1].tx_time_ns, 5'000'000 / 2) << "one period apart, not bunched";
  }
}

TEST(StrobeEdgePairer, PairsActiveAndInactiveEdgesIntoExposures) {
  StrobeEdgePairer p;
  EXPECT_FALSE(p.edge(false, 50));  // started mid-exposure: no start seen
  EXPECT_FALSE(p.edge(true, 100));
  auto e = p.edge(false, 130);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->frame, 0);
  EXPECT_EQ(e->timestamp_ns, 100);
  EXPECT_EQ(e->exposure_ns, 30);
  EXPECT_FALSE(p.edge(true, 200));
  EXPECT_EQ(p.edge(false, 240)->frame, 1);
}

TEST(StrobeEdgePairer, NumbersByTimeSoThatAMissedPulseSkipsAFrame) {
  StrobeEdgePairer p(1000);
  std::vector<int64_t> frames;
  for (int64_t start : {10'000, 11'003, 13'998, 15'001}) {  // the pulse at ~12'000 was missed
    p.edge(true, start);
    frames.push_back(p.edge(false, start + 200)->frame);
  }
  EXPECT_EQ(frames, (std::vector<int64_t>{0, 1, 4, 5}));
}

TEST(ExposureLogWriter, WritesTheHeaderAndOneFlushedRowPerExposure) {
  const std::string path = ::testing::TempDir() + "/exposures.csv";
  auto w = ExposureLogWriter::create(path);
  ASSERT_TRUE(w) << w.error().what();
  ASSERT_TRUE((*w)->write(Exposure{0, -5, 7}));
  ASSERT_TRUE((*w)->write(Exposure{3, 1'234'567'890'123, 5'000'000}));
  std::ifstream in(path);  // read while the writer is open: rows are flushed
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "frame,timestamp_ns,exposure_ns\n0,-5,7\n3,1234567890123,5000000\n");
  auto bad = ExposureLogWriter::create("/nonexistent/dir/exposures.csv");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, HostErrorKind::kBadFile);
}

}  // namespace
}  // namespace tetrapulse::host
