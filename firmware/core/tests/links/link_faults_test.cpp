// The board's links under faults, on the simulated board: CAN frames lost, cut short,
// repeated, corrupted or random, the controller error-passive and bus-off, while CAN sync
// runs; UART garbage and truncated frames. Every good request is answered, every fault is
// counted in the status, the servo stays locked, nothing crashes.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

#include "board_testing.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;

constexpr uint8_t kNode = 1;  // SimBoardOptions' default

// The CAN frames of `m` from the host to the board.
std::vector<tp::CanFrame> frames_of(tp::CanTransferSender& sender, const tp::Message& m) {
  uint8_t bytes[tp::kMaxMessageSize];
  tp::ByteWriter w(bytes, sizeof(bytes));
  EXPECT_TRUE(tp::encode(m, w).ok());
  std::vector<tp::CanFrame> out;
  sender.send(tp::kCanPriorityRequest, kNode, w.view(), [&](const tp::CanFrame& f) {
    out.push_back(f);
    return tp::Status{};
  });
  return out;
}

// Answers on CAN with seq `seq`, since the last call.
int answers_with_seq(TestBoard& b, uint8_t seq) {
  int n = 0;
  for (const std::vector<uint8_t>& bytes : b.host.receive(LinkKind::kCan)) {
    const tp::Result<tp::Message> m = tp::decode(tp::ByteView{bytes.data(), bytes.size()});
    if (m && m->seq == seq) ++n;
  }
  return n;
}

protocol::Config can_synced_config() {
  protocol::Config c = edge_rich_config(kMs);
  c.sync_source = tp::SyncSource::kCan;
  return c;
}

enum class CanFault { kLostFrame, kCutShort, kRepeated, kCorrupted, kRandom, kControllerError };
constexpr const char* kFaultNames[] = {"a frame lost",   "cut short",  "a frame repeated",
                                       "a byte flipped", "random frame", "controller error (error-passive)"};

TEST(CanLinkFaults, EveryFaultCountedEveryGoodRequestAnsweredAndSyncKeepsItsLock) {
  sim_board::SimBoardOptions o;
  o.clock_ppm = 40;
  TestBoard b(o);
  const int64_t start = 1 * kSecond, end = start + 60 * kSecond, bus_off_from = start + 40 * kSecond,
                bus_off_to = bus_off_from + 2 * kSecond;
  b.board.advance_to(start - 100 * kMs);
  b.configure(can_synced_config());
  std::mt19937 rng(11);
  std::uniform_int_distribution<int64_t> jitter(0, 50'000);
  tp::CanTransferSender sender(tp::kCanHostNode);
  // A multi-frame request (SetConfig: 13 frames) and a single-frame one to check answers.
  const tp::Message set_config{0, tp::SetConfig{can_synced_config()}};
  int64_t locked_at = -1;
  int faults[6] = {}, good = 0, answered = 0, unlocked = 0, bus_off_seen = 0;
  uint8_t seq = 100;
  uint16_t sync_seq = 0;
  for (int64_t t = start; t < end; t += 100 * kMs, ++sync_seq) {
    const int64_t late = jitter(rng);
    b.host.send(LinkKind::kCan, tp::Message{0, tp::Sync{sync_seq}}, t + late);
    b.host.send(LinkKind::kCan, tp::Message{0, tp::FollowUp{sync_seq, t}}, t + late + kMs);
    if (t == bus_off_from) b.board.can_controller_error(true);
    if (t == bus_off_to) b.board.can_controller_error(false);
    const tp::StatusReport s = b.board.status();
    if (locked_at < 0 && s.sync_state == tp::SyncState::kLocked) locked_at = t;
    if (locked_at >= 0 && s.sync_state != tp::SyncState::kLocked) ++unlocked;
    if (locked_at < 0) continue;
    const bool bus_off = t >= bus_off_from && t < bus_off_to;
    if (bus_off) {
      bus_off_seen += s.can_bus_off != 0;
      continue;
    }
    // One fault, then a good request that must be answered.
    const auto kind = static_cast<CanFault>(sync_seq % 6);
    std::vector<tp::CanFrame> frames = frames_of(sender, tp::Message{++seq, set_config.body});
    switch (kind) {
      case CanFault::kLostFrame: frames.erase(frames.begin() + 1 + static_cast<std::ptrdiff_t>(rng() % (frames.size() - 2))); break;
      case CanFault::kCutShort: frames.resize(1 + rng() % (frames.size() - 1)); break;
      case CanFault::kRepeated: frames.insert(frames.begin() + 3, frames[2]); break;
      case CanFault::kCorrupted: {
        tp::CanFrame& f = frames[rng() % frames.size()];
        f.data[rng() % f.size] ^= static_cast<uint8_t>(1u << (rng() % 8));
        break;
      }
      case CanFault::kRandom: {
        frames.resize(1);
        for (uint8_t i = 0; i < frames[0].size; ++i) frames[0].data[i] = static_cast<uint8_t>(rng());
        break;
      }
      case CanFault::kControllerError:
        frames.clear();
        b.board.can_controller_error(false);
        break;
    }
    ++faults[static_cast<int>(kind)];
    const int64_t at = t + 20 * kMs;
    for (const tp::CanFrame& f : frames) b.board.can_frame(f, at);
    b.board.advance_to(at + 2 * kMs);
    b.host.receive(LinkKind::kCan);  // whatever the fault got (an error, an Ack of a repeat)
    ++good;
    for (const tp::CanFrame& f : frames_of(sender, tp::Message{++seq, tp::GetStatus{}})) b.board.can_frame(f, at + 3 * kMs);
    b.board.advance_to(at + 5 * kMs);
    answered += answers_with_seq(b, seq);
  }
  b.board.advance_to(end);
  ASSERT_GE(locked_at, 0) << "never locked";
  const tp::StatusReport s = b.board.status();
  const EdgeTiming after = edge_timing(b.board, tp::TimeBase{0, kMs}, locked_at, end);
  std::printf("[measure] CAN faults while synced: lost %d, cut short %d, repeated %d, flipped %d, random %d,"
              " controller errors %d, 2 s bus-off; %d/%d good requests answered; status can_errors %u,"
              " rx_malformed %u, bus-off shown %d times; LED edges within %.1f us, %d samples out of lock\n",
              faults[0], faults[1], faults[2], faults[3], faults[4], faults[5], answered, good, s.can_errors,
              s.rx_malformed, bus_off_seen, after.max_abs_ns / 1e3, unlocked);
  for (int k = 0; k < 6; ++k) EXPECT_GT(faults[k], 0) << "no fault of kind '" << kFaultNames[k] << "' was injected";
  EXPECT_EQ(answered, good) << "a good request after a fault was not answered";
  EXPECT_EQ(bus_off_seen, 20) << "the status shows bus-off all the time it lasts";
  EXPECT_EQ(s.can_bus_off, 0) << "recovered";
  EXPECT_GE(s.can_errors, faults[5] + 2) << "controller errors and the bus-off counted";
  EXPECT_EQ(unlocked, 0) << "sync keeps its lock";
  EXPECT_LT(after.max_abs_ns, 50'000.0);
}

TEST(UartLinkFaults, GarbageAndTruncatedFramesCostOnlyThemselves) {
  TestBoard b{sim_board::SimBoardOptions{}};
  std::mt19937 rng(5);
  const auto frame_of = [](const tp::Message& m) {
    uint8_t bytes[tp::kMaxMessageSize], frame[tp::kUartMaxFrameSize];
    tp::ByteWriter w(bytes, sizeof(bytes));
    EXPECT_TRUE(tp::encode(m, w).ok());
    const tp::Result<size_t> n = tp::encode_uart_frame(w.view(), frame, sizeof(frame));
    EXPECT_TRUE(n.ok());
    return std::vector<uint8_t>(frame, frame + *n);
  };
  int garbage = 0, truncated = 0, good = 0, answered = 0;
  uint8_t seq = 0;
  int64_t t = kSecond;
  for (int round = 0; round < 300; ++round, t += 10 * kMs) {
    std::vector<uint8_t> noise;
    if (round % 2 == 0) {
      noise.resize(1 + rng() % 300);  // line noise, zeros and all
      for (uint8_t& x : noise) x = static_cast<uint8_t>(rng());
      ++garbage;
    } else {
      noise = frame_of(tp::Message{++seq, tp::SetConfig{edge_rich_config(kMs)}});
      noise.resize(1 + rng() % (noise.size() - 1));  // cut short, no delimiter
      ++truncated;
    }
    b.board.uart_bytes(tp::ByteView{noise.data(), noise.size()}, t);
    // A sender flushes line noise with a delimiter before its frame (SPEC.md §6).
    std::vector<uint8_t> request{tp::kUartDelimiter};
    const uint8_t want = ++seq;
    const std::vector<uint8_t> f = frame_of(tp::Message{want, tp::GetStatus{}});
    request.insert(request.end(), f.begin(), f.end());
    b.board.uart_bytes(tp::ByteView{request.data(), request.size()}, t + kMs);
    ++good;
    for (const std::vector<uint8_t>& bytes : b.host.receive(LinkKind::kUart)) {
      const tp::Result<tp::Message> m = tp::decode(tp::ByteView{bytes.data(), bytes.size()});
      if (m && m->seq == want && m->get<tp::StatusReport>() != nullptr) ++answered;
    }
  }
  const tp::StatusReport s = b.board.status();
  std::printf("[measure] UART: %d bursts of garbage, %d truncated frames: %d/%d good requests answered,"
              " rx_malformed %u\n",
              garbage, truncated, answered, good, s.rx_malformed);
  EXPECT_EQ(answered, good);
  EXPECT_GT(s.rx_malformed, 0u) << "the faults are counted";
  ASSERT_NE(b.board.firmware(), nullptr);
}

}  // namespace
}  // namespace tetrapulse::fw::testing
