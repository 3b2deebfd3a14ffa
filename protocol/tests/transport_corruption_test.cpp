// Every truncation and every single-bit flip of every golden frame gives a message or
// a typed error, never a crash (run under ASan/UBSan in the asan preset), and the
// decoders recover for the next, intact frame.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "vector_file.hpp"

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

std::vector<testing::VectorFile> read_all(const std::string& part, const std::string& prefix = "") {
  auto files = testing::read_vector_dir(testing::vectors_dir(part), prefix);
  EXPECT_TRUE(files.has_value()) << files.error();
  return files ? std::move(*files) : std::vector<testing::VectorFile>{};
}

// How corrupted inputs came out.
struct Tally {
  size_t trials = 0, errors = 0, original = 0, other = 0;
  void print(const char* what) const {
    std::printf("%s: %zu corruptions -> %zu errors/nothing, %zu original message, %zu other message\n",
                what, trials, errors, original, other);
  }
};

bool valid_message(ByteView m) { return m.size >= 3 && m.size <= kMaxMessageSize && m.data != nullptr; }

std::vector<CanFrame> can_frames(const testing::VectorFile& f) {
  std::vector<CanFrame> out;
  for (const auto* r : f.all("frame")) {
    CanFrame c;
    c.id = static_cast<uint32_t>(r->fields.at("id"));
    for (uint8_t b : r->bytes) c.data[c.size++] = b;
    out.push_back(c);
  }
  return out;
}

// Feeds a (damaged) frame stream then the intact one; the intact transfer must come
// through after at most the timeout.
void run_can(const std::vector<CanFrame>& damaged, const std::vector<CanFrame>& intact, const Bytes& original,
             Tally* tally) {
  CanReceiveSession sessions[2];
  CanTransferReceiver rx(sessions, 2, 1000);
  ++tally->trials;
  bool any = false;
  int64_t t = 0;
  for (const CanFrame& f : damaged) {
    const CanReceiveOutcome out = rx.accept(f, t++);
    ASSERT_TRUE(out.verdict != CanFrameVerdict::kDropped || out.fault != CanFault::kNone);
    if (out.verdict != CanFrameVerdict::kComplete) continue;
    ASSERT_TRUE(valid_message(out.transfer.message));
    any = true;
    if (Bytes(out.transfer.message.begin(), out.transfer.message.end()) == original) {
      ++tally->original;
    } else {
      ++tally->other;
    }
  }
  if (!any) ++tally->errors;
  t += 2000;  // past the timeout: the intact copy is a new transfer even with the same transfer-id
  Bytes recovered;
  for (const CanFrame& f : intact) {
    const CanReceiveOutcome out = rx.accept(f, t++);
    if (out.verdict == CanFrameVerdict::kComplete) recovered.assign(out.transfer.message.begin(), out.transfer.message.end());
  }
  EXPECT_EQ(recovered, original);
}

TEST(TransportCorruption, CanFrames) {
  Tally tally;
  for (const auto& file : read_all("can", "")) {
    SCOPED_TRACE(file.path);
    const std::vector<CanFrame> frames = can_frames(file);
    const Bytes original = file.first("message")->bytes;
    for (size_t i = 0; i < frames.size(); ++i) {
      // The stream cut after frame i, and frame i cut short.
      run_can(std::vector<CanFrame>(frames.begin(), frames.begin() + static_cast<long>(i)), frames, original, &tally);
      for (uint8_t size = 0; size < frames[i].size; ++size) {
        auto damaged = frames;
        damaged[i].size = size;
        run_can(damaged, frames, original, &tally);
      }
      // Every bit of the identifier (29) and of the data.
      for (int bit = 0; bit < 29 + 8 * frames[i].size; ++bit) {
        auto damaged = frames;
        if (bit < 29) {
          damaged[i].id ^= 1u << bit;
        } else {
          damaged[i].data[(bit - 29) / 8] ^= static_cast<uint8_t>(1u << ((bit - 29) % 8));
        }
        run_can(damaged, frames, original, &tally);
      }
    }
  }
  tally.print("CAN");
  EXPECT_GT(tally.errors, tally.trials / 2);
}

TEST(TransportCorruption, UartFrames) {
  Tally tally;
  for (const auto& file : read_all("uart", "")) {
    SCOPED_TRACE(file.path);
    const Bytes frame = file.first("frame")->bytes;
    const Bytes original = file.first("message")->bytes;
    std::vector<Bytes> damaged;
    for (size_t n = 0; n < frame.size(); ++n) {
      Bytes cut(frame.begin(), frame.begin() + static_cast<long>(n));
      cut.push_back(0x00);  // the line carries on with a delimiter
      damaged.push_back(cut);
    }
    for (size_t bit = 0; bit < 8 * frame.size(); ++bit) {
      Bytes flipped = frame;
      flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      flipped.push_back(0x00);  // ends the frame if the flip removed its delimiter
      damaged.push_back(flipped);
    }
    for (const Bytes& d : damaged) {
      UartFrameDecoder decoder;
      ++tally.trials;
      bool any = false;
      Bytes stream = d;
      stream.insert(stream.end(), frame.begin(), frame.end());
      size_t at = 0;
      Bytes last;
      while (at < stream.size()) {
        size_t used = 0;
        const ReceiveEvent e = decoder.feed(ByteView{stream.data() + at, stream.size() - at}, &used);
        const bool in_damaged_part = at + used <= d.size();
        at += used;
        if (e.kind == ReceiveKind::kError) {
          ASSERT_NE(e.error, Error::kNone);
        }
        if (e.kind != ReceiveKind::kMessage) continue;
        ASSERT_TRUE(valid_message(e.message));
        last.assign(e.message.begin(), e.message.end());
        if (!in_damaged_part) continue;
        any = true;
        if (last == original) {
          ++tally.original;
        } else {
          ++tally.other;
        }
      }
      if (!any) ++tally.errors;
      EXPECT_EQ(last, original) << "the intact frame after the damage was lost";
    }
  }
  tally.print("UART");
  // CRC-16 catches every single-bit error in the decoded bytes; a flip that moves COBS
  // structure changes several bytes, which the measured count shows it also caught.
  EXPECT_EQ(tally.other, 0u);
}

TEST(TransportCorruption, UsbBulkTransfers) {
  Tally tally;
  for (const auto& file : read_all("usb", "bulk_")) {
    SCOPED_TRACE(file.path);
    const Bytes transfer = file.first("transfer")->bytes;
    const Bytes original = file.first("message")->bytes;
    for (size_t n = 0; n < transfer.size(); ++n) {
      ++tally.trials;
      const Result<ByteView> r = decode_usb_bulk_frame(ByteView{transfer.data(), n});
      EXPECT_FALSE(r.ok()) << "truncated to " << n;
      ++tally.errors;
    }
    for (size_t bit = 0; bit < 8 * transfer.size(); ++bit) {
      Bytes flipped = transfer;
      flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      ++tally.trials;
      const Result<ByteView> r = decode_usb_bulk_frame(ByteView{flipped.data(), flipped.size()});
      if (!r) {
        ++tally.errors;
        EXPECT_LT(bit, 16u) << "only the length field is checked";
        continue;
      }
      ASSERT_TRUE(valid_message(*r));
      ++tally.other;  // USB's own packet CRC protects the data; this framing adds none
    }
  }
  tally.print("USB bulk");
}

TEST(TransportCorruption, DfuStatus) {
  Tally tally;
  for (const auto& file : read_all("usb", "dfu_status_")) {
    const Bytes bytes = file.first("bytes")->bytes;
    for (size_t n = 0; n < bytes.size(); ++n) {
      ++tally.trials;
      EXPECT_EQ(decode_dfu_status(ByteView{bytes.data(), n}).error(), Error::kTruncated);
      ++tally.errors;
    }
    for (size_t bit = 0; bit < 8 * bytes.size(); ++bit) {
      Bytes flipped = bytes;
      flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      ++tally.trials;
      const Result<DfuStatus> r = decode_dfu_status(ByteView{flipped.data(), flipped.size()});
      if (!r) {
        EXPECT_EQ(r.error(), Error::kBadValue);
        ++tally.errors;
        continue;
      }
      EXPECT_LE(static_cast<uint8_t>(r->state), kDfuLastState);
      EXPECT_LE(static_cast<uint8_t>(r->status), kDfuLastStatusCode);
      ++tally.other;
    }
  }
  tally.print("DFU status");
}

}  // namespace
}  // namespace tetrapulse::protocol
