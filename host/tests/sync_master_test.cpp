// The sync master's logic without hardware (tests/vm/board runs it on vcan and gpio-sim):
// CanSync's Sync/FollowUp pairs and their transmit-time sources over an in-memory bus, the
// strobe edge pairing, and the exposures file.
#include <gtest/gtest.h>

#include <deque>
#include <fstream>
#include <sstream>

#include "can_board_responder.hpp"
#include "fake_can_bus.hpp"
#include "tetrapulse/host/can_sync.hpp"
#include "tetrapulse/host/exposure.hpp"
#include "tetrapulse/host/gpio_sync.hpp"

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
  constexpr int64_t kPeriod = 5'000'000;
  const int64_t before = RigClock().now();
  auto sent = sync->run(stop, 4, [&](const CanSyncSample& s) { samples.push_back(s); });
  ASSERT_TRUE(sent) << sent.error().what();
  EXPECT_EQ(*sent, 4u);
  ASSERT_EQ(samples.size(), 4u);
  // Sync k is due at slot k = (the whole period after the start) + k periods and never
  // leaves before it (a loaded host may make it late, which this does not judge).
  const int64_t slot0 = (before / kPeriod + 1) * kPeriod;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (i > 0) {
      EXPECT_EQ(samples[i].sync_seq, samples[i - 1].sync_seq + 1);
    }
    EXPECT_GE(samples[i].tx_time_ns, slot0 + static_cast<int64_t>(i) * kPeriod) << "sync " << i << " went out early";
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


// A GPIO line on a clock the test moves: sleeping jumps to the time asked for (plus a
// scripted lateness), setting the line takes `set_ns`, and input edges come from a script.
class ScriptedLine final : public GpioSyncLine {
 public:
  int64_t clock = 0;
  int64_t set_ns = 3'000;                   // the set-value call takes this long
  std::vector<std::pair<int64_t, bool>> levels;  // (time, active) as set
  std::deque<Edge> input;                   // edges to report, in order
  int64_t late_at = -1;                     // one sleep that overshoots by `late_by`
  int64_t late_by = 0;

 private:
  const std::string& do_name() const override { return name_; }
  int64_t do_now() const override { return clock; }
  bool do_sleep_until(int64_t t, const std::atomic<bool>& stop) override {
    if (stop.load()) return false;
    if (t > clock) clock = t;
    if (t == late_at) clock += late_by;
    return true;
  }
  HostResult<int64_t> do_set(bool active) override {
    clock += set_ns;
    levels.emplace_back(clock - set_ns / 2, active);
    return clock - set_ns / 2;
  }
  HostResult<std::vector<Edge>> do_wait_edges(int64_t timeout_ns) override {
    std::vector<Edge> out;
    while (!input.empty() && input.front().rig_ns <= clock + timeout_ns) {
      out.push_back(input.front());
      input.pop_front();
    }
    clock += timeout_ns;
    return out;
  }

  std::string name_ = "gpio:scripted";
};

TEST(GpioSync, TriggerPulsesAtTheFrameGridAndReportsWhenTheLineReallyChanged) {
  auto line = std::make_unique<ScriptedLine>();
  ScriptedLine* l = line.get();
  l->clock = 95'000'000;
  GpioTriggerOptions o;
  o.frame_period_ns = 10'000'000;
  o.exposure_ns = 2'000'000;
  auto trigger = GpioSync::trigger(o, std::move(line));
  ASSERT_TRUE(trigger) << trigger.error().what();
  EXPECT_EQ((*trigger)->first_edge_ns(), 100'000'000) << "the next whole period at least 1 ms away";
  std::atomic<bool> stop{false};
  std::vector<Exposure> seen;
  auto n = (*trigger)->run(stop, 3, [&](const Exposure& e) { seen.push_back(e); });
  ASSERT_TRUE(n) << n.error().what();
  ASSERT_EQ(seen.size(), 3u);
  for (int64_t k = 0; k < 3; ++k) {
    EXPECT_EQ(seen[static_cast<size_t>(k)].frame, k);
    EXPECT_EQ(seen[static_cast<size_t>(k)].timestamp_ns, 100'000'000 + k * 10'000'000 + 1'500);
    EXPECT_EQ(seen[static_cast<size_t>(k)].exposure_ns, 2'000'000);
  }
  // A later run goes on with the next pulse; a pulse set late is stamped when it happened.
  l->late_at = 130'000'000;
  l->late_by = 6'000'000;
  seen.clear();
  n = (*trigger)->run(stop, 2, [&](const Exposure& e) { seen.push_back(e); });
  ASSERT_TRUE(n);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].frame, 3);
  EXPECT_EQ(seen[0].timestamp_ns, 136'000'000 + 1'500);
  EXPECT_EQ(seen[1].frame, 4);
  // A host busy for more than half a period skips to the next pulse on time: frame
  // numbers stay on the grid (5 is missed).
  l->clock = 156'000'000;
  seen.clear();
  n = (*trigger)->run(stop, 1, [&](const Exposure& e) { seen.push_back(e); });
  ASSERT_TRUE(n);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].frame, 6);
  EXPECT_EQ(seen[0].timestamp_ns, 160'000'000 + 1'500);
  auto bad = GpioSync::trigger(GpioTriggerOptions{GpioLineAddress{}, 10, 10, false, {}}, std::make_unique<ScriptedLine>());
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().what().find("gpio:scripted: exposure 10 ns"), std::string::npos) << bad.error().what();
}

TEST(GpioSync, StrobeEdgesBecomeExposuresInRigTime) {
  auto line = std::make_unique<ScriptedLine>();
  for (int64_t start : {1'000'000, 11'000'000, 41'000'000}) {  // frames 2 and 3 never strobed
    line->input.push_back(GpioSyncLine::Edge{true, start});
    line->input.push_back(GpioSyncLine::Edge{false, start + 2'500'000});
  }
  GpioStrobeOptions o;
  o.frame_period_ns = 10'000'000;
  auto strobe = GpioSync::strobe(o, std::move(line));
  std::atomic<bool> stop{false};
  std::vector<Exposure> seen;
  auto n = strobe->run(stop, 3, [&](const Exposure& e) { seen.push_back(e); });
  ASSERT_TRUE(n) << n.error().what();
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].timestamp_ns, 1'000'000);
  EXPECT_EQ(seen[0].exposure_ns, 2'500'000);
  EXPECT_EQ(seen[1].frame, 1);
  EXPECT_EQ(seen[2].frame, 4);
  EXPECT_EQ(seen[2].timestamp_ns, 41'000'000);
}

}  // namespace
}  // namespace tetrapulse::host
