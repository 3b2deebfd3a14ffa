// The command handler on the simulated board: every golden and malformed vector, and the
// behaviour of each request (SPEC.md §2.3, §3).
#include <gtest/gtest.h>

#include <vector>

#include "board_testing.hpp"
#include "tetrapulse/fw/storage/config_store.hpp"
#include "vector_cases.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::Error;
using protocol::MessageType;
using protocol::testing::VectorCase;

// Everything a message could change, except the diagnostic counters (rx_malformed,
// last_error) that exist to count bad messages.
struct Snapshot {
  std::vector<uint8_t> flash;
  std::vector<uint8_t> config;
  protocol::UpdateState update = protocol::UpdateState::kIdle;
  bool identifying = false;
  uint32_t led_log_next = 0;
  uint32_t servo_generation = 0;
  uint32_t sync_accepted = 0;
  uint32_t sync_rejected = 0;
  protocol::SyncState sync_state = protocol::SyncState::kFreeRunning;

  bool operator==(const Snapshot& o) const {
    return flash == o.flash && config == o.config && update == o.update && identifying == o.identifying &&
           led_log_next == o.led_log_next && servo_generation == o.servo_generation &&
           sync_accepted == o.sync_accepted && sync_rejected == o.sync_rejected && sync_state == o.sync_state;
  }
};

Snapshot snapshot(sim_board::SimBoard& board) {
  Snapshot s;
  const BoardState& st = board.firmware()->board();
  s.flash = board.flash().contents();
  uint8_t buf[protocol::kConfigSize];
  protocol::ByteWriter w(buf, sizeof(buf));
  EXPECT_TRUE(protocol::encode_config(st.config(), w).ok());
  s.config.assign(buf, buf + w.size());
  s.update = st.update().state();
  s.identifying = st.player().identifying();
  s.led_log_next = st.led_log().next_seq();
  s.servo_generation = st.sync().servo().generation();
  const protocol::StatusReport r = board.status();
  s.sync_accepted = r.sync_accepted;
  s.sync_rejected = r.sync_rejected;
  s.sync_state = r.sync_state;
  return s;
}

struct HandlerBoard : TestBoard {
  HandlerBoard() : TestBoard(sim_board::SimBoardOptions{}) {
    board.advance_to(50 * kMs);  // the LED schedule is full; polls at one instant add nothing
  }
  // The message straight into the firmware's command handler; the decoded answer, if any.
  std::optional<protocol::Message> handle(const std::vector<uint8_t>& bytes) {
    uint8_t out[protocol::kMaxMessageSize];
    const CommandReply r = board.firmware()->handle(protocol::ByteView{bytes.data(), bytes.size()}, board.tick(),
                                                   LinkKind::kCan, out, sizeof(out));
    board.firmware()->poll();
    if (r.size == 0) return std::nullopt;
    const protocol::Result<protocol::Message> m = protocol::decode(protocol::ByteView{out, r.size});
    EXPECT_TRUE(m.ok()) << "the handler wrote a message that does not decode";
    if (!m) return std::nullopt;
    return *m;
  }
};

class MalformedVector : public ::testing::TestWithParam<VectorCase> {};

TEST_P(MalformedVector, GetsTypedErrorOrIsDroppedAndChangesNothing) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  const Error expected = protocol::testing::expected_error(c.record);
  HandlerBoard b;
  const Snapshot before = snapshot(b.board);
  const uint16_t malformed_before = b.board.status().rx_malformed;
  const std::optional<protocol::Message> answer = b.handle(c.record.bytes);
  EXPECT_TRUE(snapshot(b.board) == before) << c.record.origin << ": state changed";
  EXPECT_EQ(b.board.status().rx_malformed, malformed_before + 1) << c.record.origin;
  const std::vector<uint8_t>& bytes = c.record.bytes;
  const bool answerable = bytes.size() >= 3 && (protocol::is_request(static_cast<MessageType>(bytes[1])) ||
                                                !protocol::is_defined(static_cast<MessageType>(bytes[1])));
  if (!answerable) {
    EXPECT_FALSE(answer.has_value()) << c.record.origin << ": answered a message that must be dropped";
    return;
  }
  ASSERT_TRUE(answer.has_value()) << c.record.origin;
  const auto* e = answer->get<protocol::ErrorResponse>();
  ASSERT_NE(e, nullptr) << c.record.origin;
  EXPECT_EQ(e->error, expected) << c.record.origin;
  EXPECT_EQ(static_cast<uint8_t>(e->request_type), bytes[1]);
  EXPECT_EQ(answer->seq, bytes[2]);
  EXPECT_EQ(b.board.status().last_error, expected);
}

INSTANTIATE_TEST_SUITE_P(CommandHandler, MalformedVector,
                         ::testing::ValuesIn(protocol::testing::vector_cases("messages/malformed")),
                         protocol::testing::case_name);

class GoldenVector : public ::testing::TestWithParam<VectorCase> {};

TEST_P(GoldenVector, RequestsAreAnsweredAndErrorsChangeNothing) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  HandlerBoard b;
  const Snapshot before = snapshot(b.board);
  const auto type = static_cast<MessageType>(c.record.bytes[1]);
  const std::optional<protocol::Message> answer = b.handle(c.record.bytes);
  if (!protocol::is_request(type)) {
    EXPECT_FALSE(answer.has_value()) << c.record.origin << ": boards never answer " << protocol::message_name(type);
    return;
  }
  ASSERT_TRUE(answer.has_value()) << c.record.origin;
  EXPECT_EQ(answer->seq, c.record.bytes[2]);
  if (const auto* e = answer->get<protocol::ErrorResponse>()) {
    EXPECT_TRUE(snapshot(b.board) == before) << c.record.origin << ": refused with " << protocol::error_name(e->error)
                                             << " but state changed";
  } else if (const auto* ack = answer->get<protocol::Ack>()) {
    EXPECT_EQ(ack->request_type, type);
  }
}

INSTANTIATE_TEST_SUITE_P(CommandHandler, GoldenVector, ::testing::ValuesIn(protocol::testing::vector_cases("messages")),
                         protocol::testing::case_name);

TEST(CommandHandler, AnswersEveryRequestWithItsResponseType) {
  HandlerBoard b;
  const protocol::Message info = b.request(protocol::GetInfo{});
  ASSERT_NE(info.get<protocol::Info>(), nullptr);
  EXPECT_EQ(info.get<protocol::Info>()->hw_model, protocol::HwModel::kSimulatedBoard);
  EXPECT_EQ(info.get<protocol::Info>()->node_id, 1);
  EXPECT_EQ(info.get<protocol::Info>()->max_code_length, 64);
  EXPECT_NE(b.request(protocol::GetConfig{}).get<protocol::ConfigReport>(), nullptr);
  EXPECT_NE(b.request(protocol::GetStatus{}).get<protocol::StatusReport>(), nullptr);
  EXPECT_NE(b.request(protocol::GetLedLog{0}).get<protocol::LedLog>(), nullptr);
  for (const protocol::Body& body : {protocol::Body{protocol::Identify{protocol::IdentifyPattern::kChase, 100}},
                                     protocol::Body{protocol::PersistConfig{}}, protocol::Body{protocol::FactoryReset{}},
                                     protocol::Body{protocol::UpdateAbort{}}}) {
    const protocol::Message m = b.request(body);
    ASSERT_NE(m.get<protocol::Ack>(), nullptr);
  }
}

TEST(CommandHandler, RefusesConfigTheBoardCannotPlayAndKeepsTheRunningOne) {
  sim_board::SimBoardOptions o;
  o.two_level = false;
  o.gpio_sync_input = false;
  TestBoard b(o);
  const protocol::Config running = b.board.firmware()->board().config();
  protocol::Config two_level = edge_rich_config(kMs);
  two_level.modulation = protocol::Modulation::kTwoLevel;
  protocol::Config gpio = edge_rich_config(kMs);
  gpio.sync_source = protocol::SyncSource::kGpio;
  for (const protocol::Config& c : {two_level, gpio}) {
    const protocol::Message m = b.request(protocol::SetConfig{c});
    ASSERT_NE(m.get<protocol::ErrorResponse>(), nullptr);
    EXPECT_EQ(m.get<protocol::ErrorResponse>()->error, Error::kNotSupported);
    EXPECT_EQ(b.board.firmware()->board().config().bit_period_ns, running.bit_period_ns);
    EXPECT_EQ(b.board.firmware()->board().config().modulation, running.modulation);
    EXPECT_EQ(b.board.firmware()->board().config().sync_source, running.sync_source);
  }
}

TEST(CommandHandler, PersistSurvivesPowerCycleAndFactoryResetRestoresDefaults) {
  TestBoard b{sim_board::SimBoardOptions{}};
  protocol::Config c = edge_rich_config(2 * kMs, 12345);
  c.target_id = 77;
  b.configure(c);
  b.board.power_cycle();
  EXPECT_EQ(b.board.firmware()->board().config().target_id, 0) << "SetConfig alone does not persist";
  b.configure(c);
  b.request(protocol::PersistConfig{});
  b.board.power_cycle();
  EXPECT_EQ(b.board.firmware()->board().config().target_id, 77);
  b.request(protocol::FactoryReset{});
  EXPECT_EQ(b.board.firmware()->board().config().target_id, 0);
  b.board.power_cycle();
  EXPECT_EQ(b.board.firmware()->board().config().target_id, 0);
  EXPECT_EQ(b.board.firmware()->board().config().bit_period_ns, protocol::default_config().bit_period_ns);
}

TEST(CommandHandler, CanAnswersComeFromTheAddressedNodeAndOthersAreIgnored) {
  sim_board::SimBoardOptions o;
  o.node_id = 9;
  TestBoard b(o);
  uint8_t buf[8];
  protocol::ByteWriter w(buf, sizeof(buf));
  ASSERT_TRUE(protocol::encode(protocol::Message{5, protocol::GetStatus{}}, w));
  b.host.send(LinkKind::kCan, w.view(), b.board.now(), 8);  // another node
  EXPECT_TRUE(b.board.take_can_frames().empty());
  b.host.send(LinkKind::kCan, w.view(), b.board.now(), 9);
  const std::vector<protocol::CanFrame> frames = b.board.take_can_frames();
  ASSERT_FALSE(frames.empty());
  const protocol::Result<protocol::CanId> id = protocol::unpack_can_id(frames[0].id);
  ASSERT_TRUE(id.ok());
  EXPECT_EQ(id->source, 9);
  EXPECT_EQ(id->destination, protocol::kCanHostNode);
  EXPECT_EQ(id->type, static_cast<uint8_t>(MessageType::kStatusReport));
}

TEST(CommandHandler, UsbControlPathAnswersThroughMessageIn) {
  TestBoard b{sim_board::SimBoardOptions{}};
  uint8_t buf[8];
  protocol::ByteWriter w(buf, sizeof(buf));
  ASSERT_TRUE(protocol::encode(protocol::Message{3, protocol::GetInfo{}}, w));
  b.board.usb_control(w.view(), b.board.now());
  EXPECT_TRUE(b.board.take_usb_bulk().empty()) << "a control-path request is answered through MESSAGE_IN";
  const std::vector<uint8_t> answer = b.board.usb_message_in();
  const protocol::Result<protocol::Message> m = protocol::decode(protocol::ByteView{answer.data(), answer.size()});
  ASSERT_TRUE(m.ok());
  EXPECT_NE(m->get<protocol::Info>(), nullptr);
  EXPECT_TRUE(b.board.usb_message_in().empty());
}

TEST(CommandHandler, LedLogPagesThroughScheduledEdgesInOrder) {
  TestBoard b{sim_board::SimBoardOptions{}};
  b.configure(edge_rich_config(kMs));
  b.board.advance_to(b.board.now() + 30 * kMs);
  uint32_t first = 0;
  uint32_t expected_seq = 0;
  bool gap_seen = false;
  for (int page = 0; page < 10; ++page) {
    const protocol::Message m = b.request(protocol::GetLedLog{first});
    const auto* log = m.get<protocol::LedLog>();
    ASSERT_NE(log, nullptr);
    for (uint8_t i = 0; i < log->count; ++i) {
      if (log->entries[i].seq != expected_seq) gap_seen = true;  // older than what the ring holds
      expected_seq = log->entries[i].seq + 1;
      EXPECT_LE(log->entries[i].marker, 3);
    }
    EXPECT_EQ(log->next, expected_seq);
    first = log->next;
  }
  EXPECT_TRUE(gap_seen) << "the ring holds only the newest edges";
  const protocol::Message m = b.request(protocol::GetLedLog{first + 1000});
  EXPECT_EQ(m.get<protocol::LedLog>()->count, 0) << "nothing after the newest edge";
}

}  // namespace
}  // namespace tetrapulse::fw::testing
