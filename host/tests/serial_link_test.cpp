// SerialLink over a pseudo-terminal pair: the golden UART frames byte for byte in both
// directions, a whole conversation with a responder on the other end, and open errors.
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <random>

#include "pty_pair.hpp"
#include "transport_vectors.hpp"
#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/serial_link.hpp"
#include "uart_responder.hpp"

namespace tetrapulse::host {
namespace {

using testing::PtyPair;
using Bytes = std::vector<uint8_t>;

// Reads exactly `n` bytes from the master end (or fewer after 2 s without data).
Bytes read_master(int fd, size_t n) {
  Bytes out;
  while (out.size() < n) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 2000) <= 0) break;
    uint8_t b[512];
    const ssize_t got = read(fd, b, std::min(sizeof(b), n - out.size()));
    if (got > 0) out.insert(out.end(), b, b + got);
  }
  return out;
}

void write_master(int fd, const Bytes& bytes) {
  size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t w = write(fd, bytes.data() + at, bytes.size() - at);
    if (w > 0) at += static_cast<size_t>(w);
  }
}

std::unique_ptr<SerialLink> open_link(const PtyPair& pty) {
  auto link = SerialLink::open(pty.device(), 115200);
  EXPECT_TRUE(link) << link.error().what();
  if (!link) return nullptr;
  EXPECT_EQ(read_master(pty.master(), 1), Bytes{0x00}) << "a delimiter first, to end line noise";
  return std::move(*link);
}

TEST(SerialLink, SendsEveryGoldenFrameByteForByte) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto link = open_link(pty);
  ASSERT_TRUE(link);
  const auto vectors = testing::wire_vectors("uart", "", "frame");
  ASSERT_GE(vectors.size(), 9u);
  for (const auto& v : vectors) {
    ASSERT_TRUE(link->send_raw(protocol::ByteView{v.message.data(), v.message.size()})) << v.file;
    EXPECT_EQ(read_master(pty.master(), v.wire.size()), v.wire) << v.file;
  }
}

TEST(SerialLink, ReceivesEveryGoldenFrameInAnyPieces) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto link = open_link(pty);
  ASSERT_TRUE(link);
  std::mt19937 random(5);
  for (const auto& v : testing::wire_vectors("uart", "", "frame")) {
    // The frame arrives in random pieces, after line noise that ends in a delimiter.
    Bytes stream = {0x13, 0x11, 0x0D, 0x00};
    stream.insert(stream.end(), v.wire.begin(), v.wire.end());
    size_t at = 0;
    while (at < stream.size()) {
      const size_t piece = std::min(stream.size() - at, size_t{1} + random() % 40);
      write_master(pty.master(), Bytes(stream.begin() + at, stream.begin() + at + piece));
      at += piece;
    }
    auto got = link->receive_raw(2'000'000'000);
    ASSERT_TRUE(got) << got.error().what();
    ASSERT_TRUE(got->has_value()) << v.file;
    EXPECT_EQ((*got)->bytes, v.message) << v.file;
  }
  EXPECT_GE(link->counters().transport_errors, 1u) << "the noise before each frame is a bad frame";
}

TEST(SerialLink, ConfiguresABoardAtTheOtherEnd) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  testing::UartResponder responder(pty.master());
  auto link = SerialLink::open(pty.device(), 921600);
  ASSERT_TRUE(link) << link.error().what();
  Board board(std::move(*link));
  auto info = board.info();
  ASSERT_TRUE(info) << info.error().what();
  EXPECT_EQ(info->hw_model, protocol::HwModel::kLinuxBoard);
  protocol::Config c;
  c.target_id = 3;
  c.codes[1] = protocol::Code{12, 0x0F3};
  // 0x03, 0x0D, 0x11, 0x13 and 0x7F are bytes a cooked tty would eat or translate.
  c.epoch_ns = 0x7F13110D03;
  ASSERT_TRUE(board.configure(c));
  auto back = board.config();
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_EQ(back->epoch_ns, c.epoch_ns);
  EXPECT_EQ(back->codes[1].bits, c.codes[1].bits);
  EXPECT_EQ(board.name(), "serial:" + pty.device());
}

TEST(SerialLink, OpenErrorsSayWhatIsWrong) {
  auto missing = SerialLink::open("/dev/tetrapulse-no-such-port");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, HostErrorKind::kNotFound);
  EXPECT_NE(missing.error().what().find("serial:/dev/tetrapulse-no-such-port: cannot open"), std::string::npos);
  auto not_tty = SerialLink::open("/dev/null");
  ASSERT_FALSE(not_tty);
  EXPECT_EQ(not_tty.error().kind, HostErrorKind::kOpenFailed);
  PtyPair pty;
  auto odd_rate = SerialLink::open(pty.device(), 12345);
  ASSERT_FALSE(odd_rate);
  EXPECT_EQ(odd_rate.error().kind, HostErrorKind::kBadInput);
}

TEST(SerialLink, TimesOutWhenNobodyAnswers) {
  PtyPair pty;
  auto link = open_link(pty);
  ASSERT_TRUE(link);
  auto r = link->request(protocol::GetStatus{}, std::chrono::milliseconds(50));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kTimeout);
}

}  // namespace
}  // namespace tetrapulse::host
