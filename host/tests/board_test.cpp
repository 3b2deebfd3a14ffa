// Board calls over a SimLink to the protocol responder: every request of SPEC.md §2.3,
// answers checked field by field, and errors that name the board and the request.
#include <gtest/gtest.h>

#include <deque>
#include <memory>

#include "responder_sim_port.hpp"
#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/sim_link.hpp"

namespace tetrapulse::host {
namespace {

using protocol::Message;
using testing::ResponderSimPort;

struct SimBoard {
  std::shared_ptr<ResponderSimPort> port = std::make_shared<ResponderSimPort>();
  Board board{std::make_unique<SimLink>("sim:7", port)};
};

protocol::Config sample_config() {
  protocol::Config c;
  c.node_id = 9;
  c.target_id = 42;
  c.codes[0] = protocol::Code{10, 0x1CB};
  c.codes[3] = protocol::Code{4, 0x5};
  c.modulation = protocol::Modulation::kTwoLevel;
  c.low_level = 12000;
  c.bit_period_ns = 5'000'000;
  c.epoch_ns = -123456789;
  c.brightness = 40000;
  c.current_limit_ma = 350;
  c.sync_source = protocol::SyncSource::kGpio;
  c.gpio_edge = protocol::GpioEdge::kFalling;
  c.gpio_edge_period_ns = 16'666'667;
  c.gpio_edge_epoch_ns = 777;
  c.gpio_edge_numbering = protocol::GpioEdgeNumbering::kCountAfterGap;
  return c;
}

bool same(const protocol::Config& a, const protocol::Config& b) {
  uint8_t x[protocol::kConfigSize], y[protocol::kConfigSize];
  protocol::ByteWriter wa(x, sizeof(x)), wb(y, sizeof(y));
  return protocol::encode_config(a, wa).ok() && protocol::encode_config(b, wb).ok() &&
         std::equal(x, x + sizeof(x), y);
}

TEST(Board, InfoCarriesTheBoardsIdentity) {
  SimBoard b;
  auto info = b.board.info();
  ASSERT_TRUE(info) << info.error().what();
  const auto& id = b.port->responder().identity();
  EXPECT_EQ(info->hw_model, id.hw_model);
  EXPECT_EQ(info->hw_revision, id.hw_revision);
  EXPECT_EQ(info->fw_version, id.fw_version);
  EXPECT_EQ(info->serial, id.serial);
  EXPECT_EQ(b.board.link().counters().sent, 1u);
  EXPECT_EQ(b.board.link().counters().received, 1u);
}

TEST(Board, ConfigureThenReadBackGivesTheSameConfig) {
  SimBoard b;
  ASSERT_TRUE(b.board.configure(sample_config()));
  auto back = b.board.config();
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_TRUE(same(*back, sample_config()));
}

TEST(Board, RebootRestoresTheStoredConfigAndPersistKeepsIt) {
  SimBoard b;
  ASSERT_TRUE(b.board.configure(sample_config()));
  ASSERT_TRUE(b.board.reboot(protocol::RebootMode::kApplication));
  EXPECT_TRUE(same(*b.board.config(), protocol::default_config()));
  ASSERT_TRUE(b.board.configure(sample_config()));
  ASSERT_TRUE(b.board.persist());
  ASSERT_TRUE(b.board.reboot(protocol::RebootMode::kApplication));
  EXPECT_TRUE(same(*b.board.config(), sample_config()));
  ASSERT_TRUE(b.board.factory_reset());
  EXPECT_TRUE(same(*b.board.config(), protocol::default_config()));
  EXPECT_EQ(b.port->responder().reboots(), 2u);
}

TEST(Board, IdentifyAndStatus) {
  SimBoard b;
  ASSERT_TRUE(b.board.identify(protocol::IdentifyPattern::kChase, 1500));
  EXPECT_EQ(b.port->responder().identify_pattern(), protocol::IdentifyPattern::kChase);
  auto status = b.board.status();
  ASSERT_TRUE(status) << status.error().what();
  EXPECT_EQ(status->update_state, protocol::UpdateState::kIdle);
  auto log = b.board.led_log(17);
  ASSERT_TRUE(log);
  EXPECT_EQ(log->next, 17u);
}

TEST(Board, RefusalNamesTheBoardTheRequestAndTheBoardsError) {
  SimBoard b;
  b.port->responder().refuse_configs(true);
  auto r = b.board.configure(sample_config());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kBoardRefused);
  EXPECT_EQ(r.error().protocol_error, protocol::Error::kNotSupported);
  EXPECT_EQ(r.error().what(), "sim:7: set_config: board refused: not_supported");
}

TEST(Board, AnInvalidConfigIsRefusedBeforeAnythingIsSent) {
  SimBoard b;
  protocol::Config c = sample_config();
  c.node_id = 0;  // 1..254
  auto r = b.board.configure(c);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kBadInput);
  EXPECT_EQ(b.board.link().counters().sent, 0u);
}

TEST(Board, SilenceIsATimeoutInSimulatedTime) {
  SimBoard b;
  b.port->lose_answers_when([](const Message&) { return true; });
  const int64_t before = b.board.link().now_ns();
  auto r = b.board.status();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kTimeout);
  EXPECT_EQ(r.error().what(), "sim:7: get_status: no answer within 1000 ms");
  EXPECT_GE(b.board.link().now_ns() - before, 1'000'000'000);
}

// A port that answers from a script: lets a test put other traffic before the answer.
class ScriptedPort : public SimBoardPort {
 public:
  std::deque<Message> script;
  std::vector<std::vector<uint8_t>> delivered;
  void deliver(protocol::ByteView m) override { delivered.emplace_back(m.begin(), m.end()); }
  void advance(int64_t ns) override { now_ += ns; }
  std::optional<std::vector<uint8_t>> take_sent() override {
    if (script.empty() || delivered.empty()) return std::nullopt;
    Message m = script.front();
    script.pop_front();
    if (m.seq == 0xEE) m.seq = delivered.back()[2];  // marker: echo the request's seq
    uint8_t buffer[protocol::kMaxMessageSize];
    protocol::ByteWriter w(buffer, sizeof(buffer));
    EXPECT_TRUE(protocol::encode(m, w));
    return std::vector<uint8_t>(buffer, buffer + w.size());
  }
  int64_t now_ns() const override { return now_; }

 private:
  int64_t now_ = 0;
};

TEST(Link, RequestSkipsStaleAnswersAndQueuesUnsolicitedMessages) {
  auto port = std::make_shared<ScriptedPort>();
  port->script.push_back(Message{200, protocol::Ack{protocol::MessageType::kGetStatus, 0}});  // stale seq
  port->script.push_back(Message{3, protocol::Sync{77}});                                 // not a response
  protocol::Info info;
  info.hw_revision = 5;
  port->script.push_back(Message{0xEE, info});
  SimLink link("sim:1", port);
  auto r = link.request(protocol::GetInfo{});
  ASSERT_TRUE(r) << r.error().what();
  ASSERT_NE(r->message.get<protocol::Info>(), nullptr);
  EXPECT_EQ(r->message.get<protocol::Info>()->hw_revision, 5);
  EXPECT_EQ(link.counters().unmatched, 1u);
  auto queued = link.receive(std::chrono::milliseconds(0));
  ASSERT_TRUE(queued);
  ASSERT_NE(queued->message.get<protocol::Sync>(), nullptr);
  EXPECT_EQ(queued->message.get<protocol::Sync>()->sync_seq, 77);
}

TEST(Link, AnswerOfTheWrongTypeIsMalformed) {
  auto port = std::make_shared<ScriptedPort>();
  port->script.push_back(Message{0xEE, protocol::Ack{protocol::MessageType::kGetInfo, 0}});
  Board board(std::make_unique<SimLink>("sim:2", port));
  auto r = board.status();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kMalformed);
  EXPECT_EQ(r.error().what(), "sim:2: get_status: answered with ack");
}

TEST(Link, BytesThatDoNotDecodeAreCountedAndDropped) {
  auto port = std::make_shared<ResponderSimPort>();
  SimLink link("sim:3", port);
  // A request with a bad version: the responder answers ErrorResponse(bad_version) (SPEC.md §3).
  const uint8_t bad[] = {0x02, 0x01, 0x09};
  port->deliver(protocol::ByteView{bad, sizeof(bad)});
  auto r = link.receive(std::chrono::milliseconds(10));
  ASSERT_TRUE(r) << r.error().what();
  const auto* e = r->message.get<protocol::ErrorResponse>();
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->error, protocol::Error::kBadVersion);
  EXPECT_EQ(r->message.seq, 9);
}

}  // namespace
}  // namespace tetrapulse::host
