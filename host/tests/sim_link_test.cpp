// SimLink against the protocol's golden vectors: every golden message
// (protocol/vectors/messages) goes to the simulated board byte for byte, and every one the
// board hands back comes out of the link as the message the vector describes, stamped with
// the board's simulated time. Malformed message vectors are counted and dropped.
#include <gtest/gtest.h>

#include <deque>

#include "golden_messages.hpp"
#include "hex_vectors.hpp"
#include "tetrapulse/host/sim_link.hpp"

namespace tetrapulse::host {
namespace {

using Bytes = std::vector<uint8_t>;
namespace pt = protocol::testing;

// A board that records what it was given and sends back what the test queued, each after
// `reply_delay_ns` of simulated time.
class RecordingBoardPort : public SimBoardPort {
 public:
  std::vector<Bytes> delivered;
  std::deque<std::pair<int64_t, Bytes>> to_send;  // (simulated time it is sent, bytes)
  int64_t now = 5'000'000;

  void deliver(protocol::ByteView m) override { delivered.emplace_back(m.begin(), m.end()); }
  void advance(int64_t ns) override { now += ns; }
  std::optional<Bytes> take_sent() override {
    if (to_send.empty() || to_send.front().first > now) return std::nullopt;
    Bytes b = std::move(to_send.front().second);
    to_send.pop_front();
    return b;
  }
  int64_t now_ns() const override { return now; }
};

Bytes encoded(const protocol::Message& m) {
  uint8_t buf[protocol::kMaxMessageSize];
  protocol::ByteWriter w(buf, sizeof(buf));
  if (!protocol::encode(m, w)) return {};
  return Bytes(w.view().begin(), w.view().end());
}

struct GoldenRecord {
  std::string key;
  Bytes bytes;
};

std::vector<GoldenRecord> golden_records() {
  std::vector<GoldenRecord> out;
  auto files = pt::read_hex_folder(pt::vectors_dir() + "/messages");
  EXPECT_TRUE(files.has_value()) << (files ? "" : files.error());
  if (!files) return out;
  for (const pt::HexFile& f : *files) {
    for (const pt::HexRecord& r : f.records) out.push_back(GoldenRecord{pt::golden_key(f.stem, r.name), r.bytes});
  }
  return out;
}

TEST(SimLink, SendsEveryGoldenMessageByteForByte) {
  const auto expected = pt::golden_messages();
  const auto records = golden_records();
  ASSERT_GE(records.size(), 20u);
  auto port = std::make_shared<RecordingBoardPort>();
  SimLink link("sim:1", port);
  size_t sent = 0;
  for (const GoldenRecord& r : records) {
    const auto m = expected.find(r.key);
    ASSERT_NE(m, expected.end()) << r.key;
    ASSERT_TRUE(link.send(m->second)) << r.key;
    ASSERT_EQ(port->delivered.size(), ++sent);
    EXPECT_EQ(port->delivered.back(), r.bytes) << r.key << ": " << pt::to_hex(port->delivered.back());
  }
}

TEST(SimLink, ReceivesEveryGoldenMessageAtTheBoardsSimulatedTime) {
  const auto expected = pt::golden_messages();
  auto port = std::make_shared<RecordingBoardPort>();
  SimLink link("sim:1", port, 100'000);
  for (const GoldenRecord& r : golden_records()) {
    const int64_t sent_at = port->now + 250'000;  // the board answers 250 us later
    port->to_send.emplace_back(sent_at, r.bytes);
    auto got = link.receive(std::chrono::milliseconds(5));
    ASSERT_TRUE(got) << r.key << ": " << got.error().what();
    EXPECT_EQ(encoded(got->message), r.bytes) << r.key;
    EXPECT_EQ(encoded(expected.at(r.key)), r.bytes) << r.key;
    // Time moves in 100 us steps while the link waits: the message is seen within one step.
    EXPECT_GE(got->received_ns, sent_at) << r.key;
    EXPECT_LT(got->received_ns, sent_at + 100'000) << r.key;
  }
  EXPECT_EQ(link.counters().malformed, 0u);
}

TEST(SimLink, MalformedVectorsAreCountedAndDropped) {
  auto files = pt::read_hex_folder(pt::vectors_dir() + "/messages/malformed");
  ASSERT_TRUE(files.has_value()) << (files ? "" : files.error());
  auto port = std::make_shared<RecordingBoardPort>();
  SimLink link("sim:1", port);
  uint32_t fed = 0;
  for (const pt::HexFile& f : *files) {
    for (const pt::HexRecord& r : f.records) {
      port->to_send.emplace_back(port->now, r.bytes);
      ++fed;
      auto got = link.receive(std::chrono::milliseconds(1));
      EXPECT_FALSE(got) << r.origin << " decoded";
      if (!got) {
        EXPECT_EQ(got.error().kind, HostErrorKind::kTimeout) << r.origin;
      }
    }
  }
  ASSERT_GT(fed, 5u);
  EXPECT_EQ(link.counters().malformed, fed);
}

}  // namespace
}  // namespace tetrapulse::host
