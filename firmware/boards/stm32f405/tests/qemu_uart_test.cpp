// The application binary under QEMU (netduinoplus2 = STM32F405), spoken to over USART1
// with the protocol's UART framing: board identity, configuration, time sync messages,
// status, and the LED edges the code player scheduled against the codes' timing.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "qemu_board.hpp"
#include "tetrapulse/protocol/timebase.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::stm32f405::testing {
namespace {

namespace tp = protocol;

tp::Message message(uint8_t seq, tp::Body body) { return request_message(seq, body); }

// Four length-10 codes, one per marker, bit i = character i (SPEC §2.5).
tp::Config test_config() {
  tp::Config c = tp::default_config();
  const uint64_t words[4] = {0b1100101101, 0b0110011011, 0b1011100010, 0b0001110111};
  for (size_t m = 0; m < 4; ++m) c.codes[m] = tp::Code{10, words[m]};
  c.modulation = tp::Modulation::kOnOff;
  c.bit_period_ns = 5'000'000;  // 5 ms: the board's 64-entry log spans ~150 ms of edges
  c.epoch_ns = 1'250'000;       // not a multiple of the period: edges must follow it
  c.sync_source = tp::SyncSource::kNone;
  return c;
}

class QemuUart : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    board_ = std::make_unique<QemuBoard>(artefact("TETRAPULSE_BOOTLOADER_ELF"), artefact("TETRAPULSE_SLOT0_IMAGE"));
  }
  static void TearDownTestSuite() { board_.reset(); }

  void SetUp() override { ASSERT_TRUE(board_ && board_->running()) << "qemu-system-arm did not start"; }

  static std::unique_ptr<QemuBoard> board_;
};
std::unique_ptr<QemuBoard> QemuUart::board_;

TEST_F(QemuUart, ReportsTheBoardItRunsOn) {
  // Bytes sent before the application enables USART1 are lost (as on a board), so the
  // first request is repeated until the board is up: at most 10 s.
  std::optional<tp::Message> reply;
  for (int attempt = 0; attempt < 50 && !reply; ++attempt) reply = board_->request(message(1, tp::GetInfo{}), 200);
  ASSERT_TRUE(reply.has_value()) << "no answer to GetInfo over USART1";
  const tp::Info* info = reply->get<tp::Info>();
  ASSERT_NE(info, nullptr) << "answered GetInfo with type " << int(static_cast<uint8_t>(reply->type()));
  EXPECT_EQ(info->protocol_version, tp::kProtocolVersion);
  EXPECT_EQ(info->hw_model, tp::HwModel::kStm32f405Reference);
  EXPECT_EQ(info->active_slot, 0);  // the image was loaded into slot 0
  EXPECT_EQ(info->fw_version, TETRAPULSE_FW_VERSION);
  // Started through the real bootloader, which reports its version in the handoff.
  EXPECT_EQ(info->bootloader_version, TETRAPULSE_FW_VERSION);
  EXPECT_NE(info->capabilities & tp::capability::kUart, 0u);
  EXPECT_NE(info->capabilities & tp::capability::kGpioSyncInput, 0u);
  // QEMU models neither the OTG core nor bxCAN (their registers read zero): the board must
  // find that out at start and not offer USB, DFU or CAN.
  EXPECT_EQ(info->capabilities & (tp::capability::kUsb | tp::capability::kDfu), 0u);
  EXPECT_EQ(info->capabilities & (tp::capability::kCan | tp::capability::kCanUpdate), 0u);
  EXPECT_EQ(board_->framing_errors(), 0u);
}

TEST_F(QemuUart, TakesConfigurationAndTimeBase) {
  const tp::Config config = test_config();
  const auto ack = board_->request(message(2, tp::SetConfig{config}));
  ASSERT_TRUE(ack.has_value());
  const tp::Ack* a = ack->get<tp::Ack>();
  ASSERT_NE(a, nullptr) << "SetConfig answered with type " << int(static_cast<uint8_t>(ack->type()));
  EXPECT_EQ(a->request_type, tp::MessageType::kSetConfig);

  const auto report = board_->request(message(3, tp::GetConfig{}));
  ASSERT_TRUE(report.has_value());
  const tp::ConfigReport* r = report->get<tp::ConfigReport>();
  ASSERT_NE(r, nullptr);
  for (size_t m = 0; m < 4; ++m) {
    EXPECT_EQ(r->config.codes[m].length, config.codes[m].length);
    EXPECT_EQ(r->config.codes[m].bits, config.codes[m].bits);
  }
  EXPECT_EQ(r->config.bit_period_ns, config.bit_period_ns);
  EXPECT_EQ(r->config.epoch_ns, config.epoch_ns);
}

TEST_F(QemuUart, TakesTimeSyncSilentlyAndReportsStatus) {
  // Sync and FollowUp are broadcasts: never answered (SPEC §2.4), never counted malformed.
  ASSERT_TRUE(board_->send(message(0, tp::Sync{7})));
  ASSERT_TRUE(board_->send(message(0, tp::FollowUp{7, 1'000'000'000})));
  const auto before = board_->request(message(4, tp::GetStatus{}));
  ASSERT_TRUE(before.has_value());
  const tp::StatusReport* s0 = before->get<tp::StatusReport>();
  ASSERT_NE(s0, nullptr) << "the first answer after Sync/FollowUp must be the StatusReport";
  EXPECT_EQ(s0->sync_source, tp::SyncSource::kNone);
  EXPECT_EQ(s0->sync_state, tp::SyncState::kFreeRunning);
  EXPECT_EQ(s0->rx_malformed, 0u);
  EXPECT_EQ(s0->update_state, tp::UpdateState::kIdle);
  // Over UART a Sync/FollowUp pair only gives coarse rig time (for numbering GPIO edges);
  // it is no sample for the clock servo, accepted or refused.
  EXPECT_EQ(s0->sync_accepted, 0u);
  EXPECT_EQ(s0->sync_rejected, 0u);

  // A broken Sync (its message one byte short, in a good frame) is counted and never
  // answered (SPEC §3: only requests get an ErrorResponse).
  uint8_t encoded[tp::kMaxMessageSize];
  tp::ByteWriter w(encoded, sizeof(encoded));
  ASSERT_TRUE(tp::encode(message(0, tp::Sync{8}), w).ok());
  std::vector<uint8_t> frame(tp::kUartMaxFrameSize);
  const tp::Result<size_t> n = tp::encode_uart_frame(tp::ByteView{encoded, w.size() - 1}, frame.data(), frame.size());
  ASSERT_TRUE(n.ok());
  frame.resize(*n);
  ASSERT_TRUE(board_->send_bytes(frame));
  const std::optional<tp::Message> unexpected = board_->receive(300);
  EXPECT_FALSE(unexpected.has_value()) << "answered a broken Sync with type "
                                       << int(static_cast<uint8_t>(unexpected->type()));
  const auto later = board_->request(message(5, tp::GetStatus{}));
  ASSERT_TRUE(later.has_value());
  const tp::StatusReport* s2 = later->get<tp::StatusReport>();
  ASSERT_NE(s2, nullptr);
  EXPECT_EQ(s2->rx_malformed, s0->rx_malformed + 1);
  EXPECT_EQ(s2->sync_accepted, 0u);
}

TEST_F(QemuUart, SchedulesLedEdgesOnTheCodesBitEdges) {
  const tp::Config config = test_config();
  const tp::TimeBase tb{config.epoch_ns, config.bit_period_ns};
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let the player run a while

  std::vector<tp::LedLogEntry> entries;
  uint32_t first = 0;
  for (int i = 0; i < 4; ++i) {
    const auto reply = board_->request(message(static_cast<uint8_t>(10 + i), tp::GetLedLog{first}));
    ASSERT_TRUE(reply.has_value());
    const tp::LedLog* log = reply->get<tp::LedLog>();
    ASSERT_NE(log, nullptr);
    for (uint8_t k = 0; k < log->count; ++k) entries.push_back(log->entries[k]);
    first = log->next;
  }
  ASSERT_GE(entries.size(), 16u) << "the code player scheduled too few edges";

  const auto status = board_->request(message(20, tp::GetStatus{}));
  ASSERT_TRUE(status.has_value());
  const tp::StatusReport* s = status->get<tp::StatusReport>();
  ASSERT_NE(s, nullptr);
  const int64_t board_now_ns = static_cast<int64_t>(s->uptime_ms) * 1'000'000;

  // Each entry: on a bit edge of the time base, with the level of that bit; per marker,
  // consecutive entries are changes and no change between them was skipped. A gap in seq
  // (entries overwritten between two GetLedLog) restarts the per-marker comparison.
  int64_t last_rig[4] = {};
  bool seen[4] = {};
  bool any[4] = {};
  uint32_t previous_seq = 0;
  for (size_t i = 0; i < entries.size(); ++i) {
    const tp::LedLogEntry& e = entries[i];
    if (i != 0) {
      EXPECT_GT(e.seq, previous_seq);
      if (e.seq != previous_seq + 1) {
        for (bool& m : seen) m = false;
      }
    }
    previous_seq = e.seq;
    ASSERT_LT(e.marker, 4);
    const tp::Code& code = config.codes[e.marker];
    EXPECT_EQ(tp::floor_mod(e.rig_time_ns - tb.epoch_ns, tb.bit_period_ns), 0) << "entry " << e.seq << " off a bit edge";
    const int64_t n = tp::bit_number(tb, e.rig_time_ns);
    const bool bit = code.bit(tp::bit_index(tb, e.rig_time_ns, code.length));
    EXPECT_EQ(e.duty, bit ? 65535 : 0) << "marker " << int(e.marker) << " bit " << n;
    // Scheduled for about now: not older than the run, not beyond the player's horizon.
    EXPECT_LT(e.rig_time_ns, board_now_ns + 50'000'000);
    EXPECT_GT(e.rig_time_ns, 0);
    if (seen[e.marker]) {
      const int64_t from = tp::bit_number(tb, last_rig[e.marker]);
      EXPECT_GT(n, from);
      const bool level = code.bit(tp::bit_index(tb, last_rig[e.marker], code.length));
      for (int64_t k = from; k < n; ++k) {
        EXPECT_EQ(code.bit(static_cast<uint32_t>(tp::floor_mod(k, code.length))), level)
            << "marker " << int(e.marker) << ": a change at bit " << k << " is missing";
      }
      EXPECT_NE(bit, level) << "marker " << int(e.marker) << ": entry at bit " << n << " is no change";
    }
    seen[e.marker] = true;
    any[e.marker] = true;
    last_rig[e.marker] = e.rig_time_ns;
  }
  for (bool marker_seen : any) {
    EXPECT_TRUE(marker_seen);
  }
  EXPECT_EQ(board_->framing_errors(), 0u);
}

// The local clock is TIM2: board uptime advances with the emulator's virtual time. On a
// board of its own whose virtual time follows the host's clock (qemu_board.hpp), uptime
// must advance as the host's clock does; the band tells a wrong tick rate (x12 for a
// missing prescaler, x2 for a wrong APB timer clock) from a right one.
TEST(QemuUartHostClock, UptimeFollowsTheTimerRate) {
  QemuBoard board(artefact("TETRAPULSE_BOOTLOADER_ELF"), artefact("TETRAPULSE_SLOT0_IMAGE"), "", VirtualClock::kHost);
  ASSERT_TRUE(board.running()) << "qemu-system-arm did not start";
  // Each uptime is read somewhere between its request's sending and its answer's
  // arrival, however late a busy host delivers either: the board's interval lies
  // between (second sent - first arrived) and (second arrived - first sent).
  using Clock = std::chrono::steady_clock;
  std::optional<tp::Message> first;
  Clock::time_point first_sent, first_arrived;
  for (int attempt = 0; attempt < 50 && !first; ++attempt) {
    first_sent = Clock::now();
    first = board.request(message(1, tp::GetStatus{}), 200);
    first_arrived = Clock::now();
  }
  ASSERT_TRUE(first.has_value()) << "no answer to GetStatus over USART1";
  const tp::StatusReport* s0 = first->get<tp::StatusReport>();
  ASSERT_NE(s0, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  const auto second_sent = Clock::now();
  const auto after = board.request(message(2, tp::GetStatus{}));
  const auto second_arrived = Clock::now();
  ASSERT_TRUE(after.has_value());
  const tp::StatusReport* s1 = after->get<tp::StatusReport>();
  ASSERT_NE(s1, nullptr);
  const double board_ms = static_cast<double>(s1->uptime_ms - s0->uptime_ms);
  const auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  const double shortest_ms = ms(second_sent - first_arrived), longest_ms = ms(second_arrived - first_sent);
  // A wrong tick rate is off by x2 or more; uptime counts whole milliseconds.
  EXPECT_GT(board_ms, 0.6 * shortest_ms) << "host interval " << shortest_ms << " to " << longest_ms << " ms";
  EXPECT_LT(board_ms, 1.4 * longest_ms + 2) << "host interval " << shortest_ms << " to " << longest_ms << " ms";
}

}  // namespace
}  // namespace tetrapulse::stm32f405::testing
