#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr int64_t kMs = 1'000'000;

Bytes random_message(std::mt19937& rng, size_t size, uint8_t type) {
  Bytes m(size);
  for (auto& b : m) b = static_cast<uint8_t>(rng());
  m[0] = kProtocolVersion;
  m[1] = type;
  return m;
}

ByteView view(const Bytes& b) { return ByteView{b.data(), b.size()}; }
Bytes bytes_of(ByteView v) { return Bytes(v.begin(), v.end()); }

std::vector<CanFrame> segment(CanTransferSender& sender, uint8_t priority, uint8_t destination,
                              const Bytes& message) {
  std::vector<CanFrame> frames(kCanMaxFramesPerTransfer);
  const Result<size_t> n = sender.segment(priority, destination, view(message), frames.data(), frames.size());
  EXPECT_TRUE(n.ok()) << error_name(n.error());
  frames.resize(n.ok() ? *n : 0);
  return frames;
}

// A receiver with its sessions, recording what it delivers.
struct Rx {
  explicit Rx(size_t sessions = 4, int64_t timeout_ns = 100 * kMs)
      : storage(sessions), receiver(storage.data(), storage.size(), timeout_ns) {}

  CanReceiveOutcome push(const CanFrame& f, int64_t t) {
    const CanReceiveOutcome out = receiver.accept(f, t);
    if (out.verdict == CanFrameVerdict::kComplete) {
      messages.push_back(bytes_of(out.transfer.message));
      transfers.push_back(out.transfer);
    }
    if (out.verdict == CanFrameVerdict::kDropped) faults.push_back(out.fault);
    return out;
  }
  void push_all(const std::vector<CanFrame>& frames, int64_t t0, int64_t step = kMs) {
    for (size_t i = 0; i < frames.size(); ++i) push(frames[i], t0 + static_cast<int64_t>(i) * step);
  }
  uint32_t fault_count(CanFault f) const { return receiver.stats().faults[static_cast<size_t>(f)]; }

  std::vector<CanReceiveSession> storage;
  CanTransferReceiver receiver;
  std::vector<Bytes> messages;
  std::vector<CanReceivedTransfer> transfers;
  std::vector<CanFault> faults;
};

TEST(CanTransferSender, FrameLayoutForEveryLength) {
  std::mt19937 rng(1);
  for (size_t size = 3; size <= kMaxMessageSize; ++size) {
    CanTransferSender sender(kCanHostNode);
    const Bytes m = random_message(rng, size, 0x21);
    const auto frames = segment(sender, kCanPriorityRequest, 5, m);
    ASSERT_EQ(frames.size(), can_frame_count(size));
    if (size <= 7) {
      ASSERT_EQ(frames.size(), 1u);
      EXPECT_EQ(frames[0].size, size + 1);
      EXPECT_EQ(frames[0].data[size], 0xE0);  // start, end, toggle, transfer-id 0
      continue;
    }
    // Message then CRC high byte first, 7 bytes per frame.
    Bytes payload;
    for (size_t i = 0; i < frames.size(); ++i) {
      const CanTail tail = decode_can_tail(frames[i].data[frames[i].size - 1]);
      EXPECT_EQ(tail.start, i == 0);
      EXPECT_EQ(tail.end, i + 1 == frames.size());
      EXPECT_EQ(tail.toggle, i % 2 == 0);
      EXPECT_EQ(tail.transfer_id, 0);
      if (i + 1 < frames.size()) {
        EXPECT_EQ(frames[i].size, 8);
      }
      EXPECT_GE(frames[i].size, 2);
      EXPECT_EQ(frames[i].id, 0x10210500u);
      payload.insert(payload.end(), frames[i].data, frames[i].data + frames[i].size - 1);
    }
    ASSERT_EQ(payload.size(), size + 2);
    const uint16_t crc = crc16_ccitt(m.data(), m.size());
    EXPECT_EQ(payload[size], crc >> 8);
    EXPECT_EQ(payload[size + 1], crc & 0xFF);
    EXPECT_TRUE(std::equal(m.begin(), m.end(), payload.begin()));
    EXPECT_EQ(crc16_ccitt(payload.data(), payload.size()), 0);  // residue of the big-endian CRC
  }
}

TEST(CanTransferSender, RejectsBadMessagesAndShortArrays) {
  CanTransferSender sender(3);
  CanFrame frames[kCanMaxFramesPerTransfer];
  Bytes two{1, 4}, too_long(kMaxMessageSize + 1, 1), ok(20, 1);
  EXPECT_EQ(sender.segment(4, 0, view(two), frames, 47).error(), Error::kBadLength);
  EXPECT_EQ(sender.segment(4, 0, view(too_long), frames, 47).error(), Error::kBadLength);
  EXPECT_EQ(sender.segment(8, 0, view(ok), frames, 47).error(), Error::kBadValue);
  EXPECT_EQ(sender.segment(4, 0, view(ok), frames, 3).error(), Error::kBufferTooSmall);
  CanTransferSender broadcast_source(kCanBroadcastNode);
  EXPECT_EQ(broadcast_source.segment(4, 0, view(ok), frames, 47).error(), Error::kBadValue);
  // Failed calls used no transfer-id.
  ASSERT_EQ(*sender.segment(4, 0, view(ok), frames, 47), 4u);
  EXPECT_EQ(decode_can_tail(frames[0].data[7]).transfer_id, 0);
  EXPECT_EQ(make_can_transfer_frame(CanTransferHeader{}, view(ok), 4).error(), Error::kBadValue);
  EXPECT_EQ(make_can_transfer_frame(CanTransferHeader{4, 0, 0, 32}, view(ok), 0).error(), Error::kBadValue);
}

TEST(CanTransferSender, TransferIdCountsPerTypeAndDestinationAndWraps) {
  CanTransferSender sender(kCanHostNode);
  for (int i = 0; i < 70; ++i) {
    EXPECT_EQ(sender.next_transfer_id(0x40, 0xFF), i % 32);
    EXPECT_EQ(sender.next_transfer_id(0x40, 3), i % 32);
    EXPECT_EQ(sender.next_transfer_id(0x41, 0xFF), i % 32);
  }
  // More (type, destination) pairs than slots: the least recently used restarts at 0.
  CanTransferSender small(kCanHostNode);
  small.next_transfer_id(1, 1);
  small.next_transfer_id(1, 1);
  for (uint8_t d = 2; d < 2 + CanTransferSender::kCounterSlots; ++d) small.next_transfer_id(1, d);
  EXPECT_EQ(small.next_transfer_id(1, 1), 0);
}

TEST(CanTransferReceiver, RoundTripsEveryLength) {
  std::mt19937 rng(2);
  CanTransferSender sender(42);
  Rx rx;
  for (size_t size = 3; size <= kMaxMessageSize; ++size) {
    const Bytes m = random_message(rng, size, static_cast<uint8_t>(size));
    const auto frames = segment(sender, kCanPriorityBulk, kCanHostNode, m);
    const int64_t t0 = static_cast<int64_t>(size) * 1000 * kMs;
    rx.push_all(frames, t0);
    ASSERT_EQ(rx.messages.size(), size - 2) << size;
    EXPECT_EQ(rx.messages.back(), m) << size;
    const CanReceivedTransfer& t = rx.transfers.back();
    EXPECT_EQ(t.timestamp_ns, t0);  // the first frame's time
    EXPECT_EQ(t.id, (CanId{kCanPriorityBulk, static_cast<uint8_t>(size), kCanHostNode, 42}));
  }
  EXPECT_TRUE(rx.faults.empty());
}

RC_GTEST_PROP(CanTransfer, RandomMessagesRoundTrip, ()) {
  const auto size = *rc::gen::inRange<size_t>(3, kMaxMessageSize + 1);
  auto m = *rc::gen::container<Bytes>(size, rc::gen::arbitrary<uint8_t>());
  const auto priority = *rc::gen::inRange<uint8_t>(0, 8);
  const auto source = *rc::gen::inRange<uint8_t>(0, 255);
  const auto destination = *rc::gen::arbitrary<uint8_t>();
  CanTransferSender sender(source);
  const auto frames = segment(sender, priority, destination, m);
  Rx rx(1);
  rx.push_all(frames, 0);
  RC_ASSERT(rx.messages.size() == 1u);
  RC_ASSERT(rx.messages[0] == m);
  RC_ASSERT(rx.transfers[0].id == (CanId{priority, m[1], destination, source}));
}

TEST(CanTransferReceiver, InterleavedTransfersFromSeveralSources) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    // Five boards, each sending three messages to the host, plus the host's own
    // broadcast of two types; frames of different transfers interleave at random but
    // each identifier's frames stay in order.
    struct Stream {
      std::vector<CanFrame> frames;
      size_t next = 0;
    };
    std::vector<Stream> streams;
    std::vector<Bytes> sent;
    for (uint8_t board = 1; board <= 5; ++board) {
      CanTransferSender sender(board);
      Stream s;
      for (int k = 0; k < 3; ++k) {
        const Bytes m = random_message(rng, 3 + rng() % 318, 0x05);
        sent.push_back(m);
        for (const CanFrame& f : segment(sender, kCanPriorityResponse, kCanHostNode, m)) s.frames.push_back(f);
      }
      streams.push_back(s);
    }
    CanTransferSender host(kCanHostNode);
    for (uint8_t type : {0x40, 0x41}) {
      const Bytes m = random_message(rng, 3 + rng() % 40, type);
      sent.push_back(m);
      streams.push_back(Stream{segment(host, kCanPrioritySync, kCanBroadcastNode, m), 0});
    }
    Rx rx(7);
    int64_t t = 0;
    for (;;) {
      std::vector<size_t> open;
      for (size_t i = 0; i < streams.size(); ++i) {
        if (streams[i].next < streams[i].frames.size()) open.push_back(i);
      }
      if (open.empty()) break;
      Stream& s = streams[open[rng() % open.size()]];
      rx.push(s.frames[s.next++], t += 100'000);
    }
    EXPECT_TRUE(rx.faults.empty());
    ASSERT_EQ(rx.messages.size(), sent.size());
    auto a = rx.messages, b = sent;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
  }
}

// The messages a frame stream delivers must each be one that was sent.
void expect_only_sent(const Rx& rx, const std::vector<Bytes>& sent) {
  for (const Bytes& m : rx.messages) {
    EXPECT_NE(std::find(sent.begin(), sent.end(), m), sent.end()) << "delivered a message never sent";
  }
}

TEST(CanTransferReceiver, LostFrameLosesOnlyItsTransfer) {
  std::mt19937 rng(4);
  for (size_t size : {8u, 20u, 60u, 265u, 320u}) {
    CanTransferSender sender(9);
    const Bytes first = random_message(rng, size, 0x22);
    const Bytes second = random_message(rng, size, 0x22);
    const auto a = segment(sender, 6, 1, first);
    const auto b = segment(sender, 6, 1, second);
    for (size_t lost = 0; lost < a.size(); ++lost) {
      Rx rx;
      auto stream = a;
      stream.erase(stream.begin() + static_cast<long>(lost));
      stream.insert(stream.end(), b.begin(), b.end());
      rx.push_all(stream, 0);
      ASSERT_EQ(rx.messages.size(), 1u) << "size " << size << " lost " << lost;
      EXPECT_EQ(rx.messages[0], second);
      // A lost first frame leaves continuations without a start; a lost middle frame
      // breaks the toggle; a lost last frame is noticed when the next transfer starts.
      const CanFault expected = lost == 0 ? CanFault::kMissingStart
                                : lost + 1 == a.size() ? CanFault::kTransferIdChanged
                                                       : CanFault::kWrongToggle;
      EXPECT_GE(rx.fault_count(expected), 1u) << "size " << size << " lost " << lost;
    }
  }
}

TEST(CanTransferReceiver, RepeatedFrameIsIgnored) {
  std::mt19937 rng(5);
  for (size_t size : {3u, 7u, 8u, 60u, 265u}) {
    CanTransferSender sender(9);
    const Bytes m = random_message(rng, size, 0x22);
    const auto frames = segment(sender, 4, 1, m);
    for (size_t dup = 0; dup < frames.size(); ++dup) {
      Rx rx;
      auto stream = frames;
      stream.insert(stream.begin() + static_cast<long>(dup) + 1, frames[dup]);
      rx.push_all(stream, 0);
      ASSERT_EQ(rx.messages.size(), 1u) << "size " << size << " repeated " << dup;
      EXPECT_EQ(rx.messages[0], m);
      EXPECT_EQ(rx.receiver.stats().duplicates, 1u);
      EXPECT_TRUE(rx.faults.empty());
    }
  }
}

TEST(CanTransferReceiver, SameBytesAfterTheTimeoutAreANewTransfer) {
  CanTransferSender sender(9);
  const Bytes m{1, 0x40, 0, 42, 0};
  const auto frames = segment(sender, 0, 0xFF, m);
  Rx rx(2, 100 * kMs);
  rx.push(frames[0], 0);
  rx.push(frames[0], 50 * kMs);   // a repeat within the timeout
  rx.push(frames[0], 200 * kMs);  // long after: a sender that restarted its counters
  EXPECT_EQ(rx.messages.size(), 2u);
  EXPECT_EQ(rx.receiver.stats().duplicates, 1u);
}

TEST(CanTransferReceiver, SwappedFramesNeverDeliverAWrongMessage) {
  std::mt19937 rng(6);
  for (size_t size : {8u, 20u, 60u, 265u}) {
    CanTransferSender sender(9);
    const Bytes first = random_message(rng, size, 0x22);
    const Bytes second = random_message(rng, size, 0x22);
    const auto a = segment(sender, 6, 1, first);
    const auto b = segment(sender, 6, 1, second);
    for (size_t i = 0; i + 1 < a.size(); ++i) {
      Rx rx;
      auto stream = a;
      std::swap(stream[i], stream[i + 1]);
      stream.insert(stream.end(), b.begin(), b.end());
      rx.push_all(stream, 0);
      ASSERT_EQ(rx.messages.size(), 1u) << "size " << size << " swapped " << i;
      EXPECT_EQ(rx.messages[0], second);
      EXPECT_FALSE(rx.faults.empty());
    }
  }
}

TEST(CanTransferReceiver, DamagedStreamsDeliverOnlySentMessages) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Bytes> sent;
    std::vector<CanFrame> stream;
    CanTransferSender sender(static_cast<uint8_t>(1 + trial % 254));
    for (int k = 0; k < 6; ++k) {
      sent.push_back(random_message(rng, 3 + rng() % 100, static_cast<uint8_t>(0x20 + rng() % 2)));
      for (const CanFrame& f : segment(sender, 4, 0, sent.back())) stream.push_back(f);
    }
    // Drop, repeat and swap frames at random.
    for (int k = 0; k < 4; ++k) {
      const size_t i = rng() % stream.size();
      switch (rng() % 3) {
        case 0: stream.erase(stream.begin() + static_cast<long>(i)); break;
        case 1: stream.insert(stream.begin() + static_cast<long>(i), stream[i]); break;
        default: if (i + 1 < stream.size()) std::swap(stream[i], stream[i + 1]);
      }
    }
    Rx rx(2);
    rx.push_all(stream, 0);
    expect_only_sent(rx, sent);
  }
}

TEST(CanTransferReceiver, TransferIdWrapsWithoutLoss) {
  std::mt19937 rng(8);
  CanTransferSender sender(7);
  Rx rx;
  int64_t t = 0;
  for (int i = 0; i < 100; ++i) {
    const Bytes m = random_message(rng, i % 2 ? 5 : 40, 0x30);
    const auto frames = segment(sender, 4, 0, m);
    rx.push_all(frames, t);
    t += 20 * kMs;
    ASSERT_EQ(rx.messages.size(), static_cast<size_t>(i + 1));
    EXPECT_EQ(rx.messages.back(), m);
    EXPECT_EQ(rx.transfers.back().transfer_id, i % 32);
  }
  EXPECT_TRUE(rx.faults.empty());
}

TEST(CanTransferReceiver, UnfinishedTransferTimesOut) {
  std::mt19937 rng(9);
  CanTransferSender sender(7);
  const Bytes first = random_message(rng, 100, 0x30);
  const Bytes second = random_message(rng, 100, 0x30);
  const auto a = segment(sender, 4, 0, first);
  const auto b = segment(sender, 4, 0, second);
  Rx rx(4, 100 * kMs);

  // A gap of exactly the timeout is still fine.
  rx.push(a[0], 0);
  for (size_t i = 1; i < a.size(); ++i) rx.push(a[i], static_cast<int64_t>(i) * 100 * kMs);
  ASSERT_EQ(rx.messages.size(), 1u);

  // Half a transfer, then silence longer than the timeout: the rest is refused and
  // the next transfer reports the one it displaced.
  for (size_t i = 0; i < 5; ++i) rx.push(b[i], 10'000 * kMs + static_cast<int64_t>(i) * kMs);
  EXPECT_EQ(rx.push(b[5], 10'200 * kMs).fault, CanFault::kMissingStart);
  EXPECT_EQ(rx.fault_count(CanFault::kTimedOut), 1u);
  const auto c = segment(sender, 4, 0, first);
  for (size_t i = 0; i < 5; ++i) rx.push(c[i], 20'000 * kMs + static_cast<int64_t>(i) * kMs);
  const CanReceiveOutcome restart = rx.push(c[0], 30'000 * kMs);
  EXPECT_EQ(restart.verdict, CanFrameVerdict::kPending);
  EXPECT_EQ(restart.fault, CanFault::kTimedOut);
  rx.push_all(std::vector<CanFrame>(c.begin() + 1, c.end()), 30'001 * kMs);
  ASSERT_EQ(rx.messages.size(), 2u);
  EXPECT_EQ(rx.transfers.back().timestamp_ns, 30'000 * kMs);

  // expire() drops idle unfinished transfers without a frame arriving.
  const auto d = segment(sender, 4, 0, second);
  rx.push(d[0], 40'000 * kMs);
  EXPECT_EQ(rx.receiver.expire(40'050 * kMs), 0u);
  EXPECT_EQ(rx.receiver.expire(40'101 * kMs), 1u);
  EXPECT_EQ(rx.fault_count(CanFault::kTimedOut), 3u);
}

TEST(CanTransferReceiver, NewTransferIdMidTransferRestarts) {
  std::mt19937 rng(10);
  CanTransferSender sender(7);
  const Bytes first = random_message(rng, 100, 0x30);
  const Bytes second = random_message(rng, 30, 0x30);
  const auto a = segment(sender, 4, 0, first);
  const auto b = segment(sender, 4, 0, second);
  Rx rx;
  rx.push_all(std::vector<CanFrame>(a.begin(), a.begin() + 3), 0);
  EXPECT_EQ(rx.push(b[0], 10 * kMs).fault, CanFault::kTransferIdChanged);
  rx.push_all(std::vector<CanFrame>(b.begin() + 1, b.end()), 11 * kMs);
  ASSERT_EQ(rx.messages.size(), 1u);
  EXPECT_EQ(rx.messages[0], second);

  // A start frame with the current transfer-id (the sender retrying) restarts too.
  const auto c = segment(sender, 4, 0, first);
  rx.push_all(std::vector<CanFrame>(c.begin(), c.begin() + 4), 100 * kMs);
  EXPECT_EQ(rx.push(c[0], 110 * kMs).fault, CanFault::kRestarted);
  rx.push_all(std::vector<CanFrame>(c.begin() + 1, c.end()), 111 * kMs);
  ASSERT_EQ(rx.messages.size(), 2u);
  EXPECT_EQ(rx.messages[1], first);
}

CanFrame frame(uint32_t id, std::initializer_list<uint8_t> data) {
  CanFrame f;
  f.id = id;
  for (uint8_t b : data) f.data[f.size++] = b;
  return f;
}

TEST(CanTransferReceiver, MalformedFramesGiveTypedFaults) {
  const uint32_t id = 0x10210301u;  // priority 4, type 0x21, to 3, from 1
  const auto fault_of = [&](std::vector<CanFrame> frames) {
    Rx rx;
    CanReceiveOutcome last;
    for (const CanFrame& f : frames) last = rx.push(f, 0);
    EXPECT_TRUE(rx.messages.empty());
    return last.verdict == CanFrameVerdict::kDropped ? last.fault : CanFault::kNone;
  };
  CanFrame empty;
  empty.id = id;
  EXPECT_EQ(fault_of({empty}), CanFault::kBadFrameSize);
  CanFrame nine = frame(id, {1, 0x21, 0, 0xE0});
  nine.size = 9;
  EXPECT_EQ(fault_of({nine}), CanFault::kBadFrameSize);
  EXPECT_EQ(fault_of({frame(0x1021FFFFu, {1, 0x21, 0, 0xE0})}), CanFault::kBadIdentifier);
  EXPECT_EQ(fault_of({frame(id | 0x01000000u, {1, 0x21, 0, 0xE0})}), CanFault::kBadIdentifier);
  EXPECT_EQ(fault_of({frame(id, {1, 0x21, 0xE0})}), CanFault::kBadLength);          // 2-byte message
  EXPECT_EQ(fault_of({frame(id, {1, 0x22, 0, 0xE0})}), CanFault::kTypeMismatch);
  EXPECT_EQ(fault_of({frame(id, {1, 0x21, 0, 0xC0})}), CanFault::kWrongToggle);     // start with toggle 0
  EXPECT_EQ(fault_of({frame(id, {1, 2, 3, 0x40})}), CanFault::kMissingStart);
  EXPECT_EQ(fault_of({frame(id, {1, 0x21, 0, 1, 2, 0xA0})}), CanFault::kShortFrame);  // short first frame
  const CanFrame start = frame(id, {1, 0x21, 0, 1, 2, 3, 4, 0xA3});
  EXPECT_EQ(fault_of({start, frame(id, {5, 6, 7, 8, 9, 10, 11, 0x23})}), CanFault::kWrongToggle);
  EXPECT_EQ(fault_of({start, frame(id, {5, 6, 7, 8, 9, 10, 11, 0x04})}), CanFault::kTransferIdChanged);
  EXPECT_EQ(fault_of({start, frame(id, {5, 6, 7, 0x03})}), CanFault::kShortFrame);       // short middle frame
  EXPECT_EQ(fault_of({start, frame(id, {0x43})}), CanFault::kBadFrameSize);             // last frame, no payload
  EXPECT_EQ(fault_of({start, frame(id, {5, 6, 7, 8, 0x43})}), CanFault::kBadCrc);
  // A 7-byte message sent as two frames: valid CRC but not how a sender cuts it.
  {
    const uint8_t m[7] = {1, 0x21, 0, 1, 2, 3, 4};
    const uint16_t crc = crc16_ccitt(m, 7);
    EXPECT_EQ(fault_of({start, frame(id, {static_cast<uint8_t>(crc >> 8), static_cast<uint8_t>(crc), 0x43})}),
              CanFault::kBadLength);
  }
  // A type byte that disagrees with the identifier, behind a valid CRC.
  {
    CanTransferSender sender(1);
    Bytes m(30, 9);
    m[0] = 1;
    m[1] = 0x22;
    auto frames = segment(sender, 4, 3, m);
    for (CanFrame& f : frames) f.id = id;
    EXPECT_EQ(fault_of(frames), CanFault::kTypeMismatch);
  }
  // 46 full frames and no end yet: the last frame cannot fit in kMaxMessageSize + 2.
  {
    std::vector<CanFrame> frames;
    for (int i = 0; i < 46; ++i) {
      const uint8_t tail = static_cast<uint8_t>((i == 0 ? 0x80 : 0) | (i % 2 == 0 ? 0x20 : 0) | 3);
      frames.push_back(frame(id, {1, 0x21, 1, 1, 1, 1, 1, tail}));
    }
    EXPECT_EQ(fault_of(frames), CanFault::kTooLong);
  }
}

TEST(CanTransferReceiver, BusySessionsRefuseNewMultiFrameTransfersButNotSingleFrames) {
  std::mt19937 rng(11);
  Rx rx(2);
  std::vector<std::vector<CanFrame>> transfers;
  for (uint8_t board = 1; board <= 3; ++board) {
    CanTransferSender sender(board);
    transfers.push_back(segment(sender, 4, 0, random_message(rng, 40, 0x30)));
  }
  rx.push(transfers[0][0], 0);
  rx.push(transfers[1][0], 0);
  EXPECT_EQ(rx.push(transfers[2][0], 0).fault, CanFault::kNoFreeSession);
  CanTransferSender sync(kCanHostNode);
  const Bytes sync_message{1, 0x40, 0, 42, 0};
  rx.push(segment(sync, 0, 0xFF, sync_message)[0], 1);
  ASSERT_EQ(rx.messages.size(), 1u);
  EXPECT_EQ(rx.messages[0], sync_message);
  // The two transfers in progress still complete.
  for (size_t i = 1; i < transfers[0].size(); ++i) {
    rx.push(transfers[0][i], 2);
    rx.push(transfers[1][i], 2);
  }
  EXPECT_EQ(rx.messages.size(), 3u);
}

TEST(CanFault, EveryFaultHasANameAndAnError) {
  for (size_t i = 1; i < kCanFaultCount; ++i) {
    const auto f = static_cast<CanFault>(i);
    EXPECT_STRNE(can_fault_name(f), "unknown_fault");
    EXPECT_NE(can_fault_error(f), Error::kNone);
  }
  EXPECT_EQ(can_fault_error(CanFault::kBadCrc), Error::kBadCrc);
  EXPECT_EQ(can_fault_error(CanFault::kTimedOut), Error::kTimeout);
}

}  // namespace
}  // namespace tetrapulse::protocol
