// One sweep over every golden vector of every kind (messages, image, can, usb, uart): each
// truncation and each single-bit flip is decoded (and, as a property, random damage to
// several bytes at once), and every case counts as decoded to a
// valid result, rejected (a typed error, or nothing delivered), a violation (a decoder broke
// its contract: an error without a name, a result that is not valid or not canonical, a
// stream that did not recover for the intact frame after the damage), or a crash. Each
// vector's cases run in a child process, so a crash is counted instead of ending the test;
// under the asan preset an out-of-bounds read is such a crash.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "message_testing.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "transport_testing.hpp"
#include "transport_vectors.hpp"
#include "vector_cases.hpp"

namespace tetrapulse::protocol::testing {
namespace {

using Bytes = std::vector<uint8_t>;

enum Outcome : char { kValid = 'v', kRejected = 'r', kViolation = 'x' };

// A golden vector and its corruptions: case i of `cases`, run and described; and the vector
// as flat bytes (`bytes`) with the outcome of any corruption of them (`decode`).
struct Subject {
  std::string kind;
  std::string origin;
  size_t cases = 0;
  std::function<Outcome(size_t)> run;
  std::function<std::string(size_t)> describe;
  Bytes bytes;
  std::function<Outcome(const Bytes&)> decode;
};

// A copy of exactly the input's size, so ASan sees any read past its end.
class Exact {
 public:
  explicit Exact(const Bytes& b) : data_(new uint8_t[b.size()]), size_(b.size()) {
    std::copy(b.begin(), b.end(), data_.get());
  }
  ByteView view() const { return ByteView{data_.get(), size_}; }

 private:
  std::unique_ptr<uint8_t[]> data_;
  size_t size_;
};

Bytes bytes_of(ByteView v) { return Bytes(v.begin(), v.end()); }
bool message_sized(ByteView m) { return m.size >= 3 && m.size <= kMaxMessageSize; }

// Byte vectors: cases 0..n-1 cut them to that length, cases n..9n-1 flip one bit each.
// `damaged` judges damage beyond one flip or cut, when it differs from `decoder`.
Subject byte_subject(const std::string& kind, const std::string& origin, const Bytes& bytes,
                     std::function<Outcome(const Bytes&)> decoder,
                     std::function<Outcome(const Bytes&)> damaged = nullptr) {
  const size_t n = bytes.size();
  const auto corrupt = [bytes, n](size_t i) {
    if (i < n) return Bytes(bytes.begin(), bytes.begin() + static_cast<long>(i));
    Bytes flipped = bytes;
    flipped[(i - n) / 8] ^= static_cast<uint8_t>(1u << ((i - n) % 8));
    return flipped;
  };
  return Subject{kind,
                 origin,
                 9 * n,
                 [corrupt, decoder](size_t i) { return decoder(corrupt(i)); },
                 [n](size_t i) {
                   return i < n ? "cut to " + std::to_string(i) + " bytes" : "bit " + std::to_string(i - n) + " flipped";
                 },
                 bytes,
                 damaged ? damaged : decoder};
}

Outcome message_outcome(const Bytes& b) {
  const auto m = decode(Exact(b).view());
  if (!m) return m.error() != Error::kNone ? kRejected : kViolation;
  return validate(*m).ok() && encode_bytes(*m) == b ? kValid : kViolation;
}

Outcome image_outcome(const Bytes& b) {
  const Exact in(b);
  const auto h = decode_image_header(in.view());
  if (!h) return h.error() != Error::kNone ? kRejected : kViolation;
  Bytes again(kImageHeaderSize);
  ByteWriter out(again.data(), again.size());
  if (!validate(*h).ok() || !encode_image_header(*h, out).ok()) return kViolation;
  (void)check_payload(*h, in.view());  // reads the payload the header describes
  return Bytes(b.begin(), b.begin() + kImageHeaderSize) == again ? kValid : kViolation;
}

Outcome dfu_status_outcome(const Bytes& b) {
  const auto s = decode_dfu_status(Exact(b).view());
  if (!s) return s.error() != Error::kNone ? kRejected : kViolation;
  uint8_t again[kDfuStatusSize];
  const auto n = encode_dfu_status(*s, again, sizeof(again));
  return n && Bytes(again, again + *n) == b ? kValid : kViolation;
}

Outcome protocol_info_outcome(const Bytes& b) {
  const auto info = decode_usb_protocol_info(Exact(b).view());
  if (!info) return info.error() != Error::kNone ? kRejected : kViolation;
  uint8_t again[kUsbProtocolInfoSize];
  const auto n = encode_usb_protocol_info(*info, again, sizeof(again));
  if (!n) return kViolation;
  for (size_t i = 0; i < *n; ++i) {
    if (i != 1 && again[i] != b[i]) return kViolation;  // byte 1 is reserved
  }
  return kValid;
}

// The damaged frame, a delimiter (the flip may have removed its own), then the intact frame:
// a message from the damaged part must be the original when `one_flip` (the CRC catches
// every single flip; damage to many bytes passes it with probability 2^-16), and the intact
// frame must come through.
Outcome uart_outcome(const Bytes& damaged, const Bytes& frame, const Bytes& original, bool one_flip) {
  Bytes stream = damaged;
  stream.push_back(kUartDelimiter);
  const size_t damaged_end = stream.size();
  stream.insert(stream.end(), frame.begin(), frame.end());
  const Exact in(stream);
  UartFrameDecoder decoder;
  Outcome outcome = kRejected;
  Bytes last;
  for (size_t at = 0; at < stream.size();) {
    size_t used = 0;
    const ReceiveEvent e = decoder.feed(in.view().subview(at, stream.size() - at), &used);
    if (used == 0) return kViolation;
    at += used;
    if (e.kind == ReceiveKind::kError && e.error == Error::kNone) return kViolation;
    if (e.kind != ReceiveKind::kMessage) continue;
    if (!message_sized(e.message)) return kViolation;
    last = bytes_of(e.message);
    if (at > damaged_end) continue;
    if (one_flip && last != original) return kViolation;
    outcome = kValid;
  }
  return last == original ? outcome : kViolation;
}

// The damaged transfer's packets, then the intact transfer's, into one receiver.
Outcome usb_bulk_outcome(const Bytes& damaged, const Bytes& transfer, const Bytes& original) {
  UsbBulkFrameReceiver rx;
  Outcome outcome = kRejected;
  for (const Bytes& p : usb_packets(damaged)) {
    const ReceiveEvent e = rx.push_packet(Exact(p).view());
    if (e.kind == ReceiveKind::kError && e.error == Error::kNone) return kViolation;
    if (e.kind != ReceiveKind::kMessage) continue;
    if (!message_sized(e.message)) return kViolation;
    outcome = kValid;  // the framing has no CRC (USB's packet CRC protects the data)
  }
  Bytes recovered;
  for (const Bytes& p : usb_packets(transfer)) {
    const ReceiveEvent e = rx.push_packet(view(p));
    if (e.kind == ReceiveKind::kMessage) recovered = bytes_of(e.message);
  }
  return recovered == original ? outcome : kViolation;
}

// CAN cases of one frame of a transfer: the stream cut before it, the frame cut to each
// shorter size, and each bit of its identifier and data flipped.
struct CanCase {
  enum What { kStreamCut, kFrameCut, kIdBitFlip, kDataBitFlip } what;
  size_t frame;
  size_t param;
};

std::vector<CanCase> can_cases(const std::vector<CanFrame>& frames) {
  std::vector<CanCase> cases;
  for (size_t i = 0; i < frames.size(); ++i) {
    cases.push_back({CanCase::kStreamCut, i, 0});
    for (size_t s = 0; s < frames[i].size; ++s) cases.push_back({CanCase::kFrameCut, i, s});
    for (size_t b = 0; b < 29; ++b) cases.push_back({CanCase::kIdBitFlip, i, b});
    for (size_t b = 0; b < 8u * frames[i].size; ++b) cases.push_back({CanCase::kDataBitFlip, i, b});
  }
  return cases;
}

std::vector<CanFrame> corrupt(const std::vector<CanFrame>& frames, const CanCase& c) {
  if (c.what == CanCase::kStreamCut) return std::vector<CanFrame>(frames.begin(), frames.begin() + static_cast<long>(c.frame));
  std::vector<CanFrame> damaged = frames;
  CanFrame& f = damaged[c.frame];
  if (c.what == CanCase::kFrameCut) f.size = static_cast<uint8_t>(c.param);
  if (c.what == CanCase::kIdBitFlip) f.id ^= 1u << c.param;
  if (c.what == CanCase::kDataBitFlip) f.data[c.param / 8] ^= static_cast<uint8_t>(1u << (c.param % 8));
  return damaged;
}

// The damaged frames, then (after the transfer timeout) the intact transfer again.
Outcome can_outcome(const std::vector<CanFrame>& damaged, const CanTransferVector& v) {
  constexpr int64_t kTimeoutNs = 1000;
  CanReceiveSession sessions[2];
  CanTransferReceiver rx(sessions, 2, kTimeoutNs);
  Outcome outcome = kRejected;
  int64_t t = 0;
  for (const CanFrame& f : damaged) {
    const CanReceiveOutcome out = rx.accept(f, t++);
    if (out.verdict == CanFrameVerdict::kDropped && out.fault == CanFault::kNone) return kViolation;
    if (out.verdict != CanFrameVerdict::kComplete) continue;
    if (!message_sized(out.transfer.message) || out.transfer.message[1] != out.transfer.id.type) return kViolation;
    outcome = kValid;  // a single frame has no transfer CRC: the bus CRC protects it
  }
  t += 2 * kTimeoutNs;
  Bytes recovered;
  for (const CanFrame& f : v.frames) {
    const CanReceiveOutcome out = rx.accept(f, t++);
    if (out.verdict == CanFrameVerdict::kComplete) recovered = bytes_of(out.transfer.message);
  }
  return recovered == v.message ? outcome : kViolation;
}

// Frames as flat bytes, each its identifier (u32 LE) then its data, and back: flat bytes cut
// short give fewer frames, the last one shorter.
Bytes flatten(const std::vector<CanFrame>& frames) {
  Bytes flat;
  for (const CanFrame& f : frames) {
    for (int i = 0; i < 4; ++i) flat.push_back(static_cast<uint8_t>(f.id >> (8 * i)));
    flat.insert(flat.end(), f.data, f.data + f.size);
  }
  return flat;
}

std::vector<CanFrame> unflatten(const Bytes& flat, const std::vector<CanFrame>& like) {
  std::vector<CanFrame> frames;
  size_t at = 0;
  for (const CanFrame& l : like) {
    if (flat.size() - at < 4) break;
    CanFrame f;
    for (size_t i = 0; i < 4; ++i) f.id |= static_cast<uint32_t>(flat[at + i]) << (8 * i);
    at += 4;
    f.size = static_cast<uint8_t>(std::min<size_t>(l.size, flat.size() - at));
    std::copy(flat.begin() + static_cast<long>(at), flat.begin() + static_cast<long>(at + f.size), f.data);
    at += f.size;
    frames.push_back(f);
  }
  return frames;
}

Subject can_subject(const CanTransferVector& v) {
  const auto cases = std::make_shared<std::vector<CanCase>>(can_cases(v.frames));
  static const char* const kWhat[] = {"stream cut before frame ", "cut to ", "identifier bit ", "data bit "};
  return Subject{"can",
                 v.path,
                 cases->size(),
                 [cases, v](size_t i) { return can_outcome(corrupt(v.frames, (*cases)[i]), v); },
                 [cases](size_t i) {
                   const CanCase& c = (*cases)[i];
                   const std::string param = c.what == CanCase::kStreamCut ? "" : std::to_string(c.param) + " of frame ";
                   return kWhat[c.what] + param + std::to_string(c.frame);
                 },
                 flatten(v.frames),
                 [v](const Bytes& flat) { return can_outcome(unflatten(flat, v.frames), v); }};
}

// Every vector file, as subjects; a file that does not read fails the test.
std::vector<Subject> subjects() {
  std::vector<Subject> out;
  const auto files = [](const std::string& folder, const std::string& prefix = "") {
    auto f = read_vectors(folder, prefix);
    EXPECT_TRUE(f.has_value()) << f.error();
    return f ? std::move(*f) : std::vector<HexFile>{};
  };
  const auto records = [&](const std::string& kind, const std::vector<HexFile>& from,
                           const std::function<Outcome(const Bytes&)>& decoder) {
    for (const HexFile& f : from) {
      for (const HexRecord& r : f.records) out.push_back(byte_subject(kind, r.origin, r.bytes, decoder));
    }
  };
  for (const char* folder : {"messages", "messages/malformed"}) records("messages", files(folder), message_outcome);
  for (const char* folder : {"image", "image/malformed"}) records("image", files(folder), image_outcome);
  for (const HexFile& f : files("can")) {
    const auto v = can_transfer_vector(f);
    EXPECT_TRUE(v.has_value()) << v.error();
    if (v) out.push_back(can_subject(*v));
  }
  for (const HexFile& f : files("uart")) {
    const Bytes frame = record_bytes(f, "frame"), message = record_bytes(f, "message");
    out.push_back(byte_subject(
        "uart", f.path, frame, [frame, message](const Bytes& d) { return uart_outcome(d, frame, message, true); },
        [frame, message](const Bytes& d) { return uart_outcome(d, frame, message, false); }));
  }
  for (const HexFile& f : files("usb", "bulk_")) {
    const Bytes transfer = record_bytes(f, "transfer"), message = record_bytes(f, "message");
    out.push_back(byte_subject("usb", f.path, transfer,
                               [transfer, message](const Bytes& d) { return usb_bulk_outcome(d, transfer, message); }));
  }
  for (const HexFile& f : files("usb", "dfu_status_")) {
    out.push_back(byte_subject("usb", f.path, record_bytes(f, "bytes"), dfu_status_outcome));
  }
  for (const HexFile& f : files("usb", "protocol_info")) {
    out.push_back(byte_subject("usb", f.path, record_bytes(f, "bytes"), protocol_info_outcome));
  }
  return out;
}

struct Counts {
  size_t cases = 0, valid = 0, rejected = 0, violations = 0, crashes = 0;
  void add(const Counts& o) {
    cases += o.cases;
    valid += o.valid;
    rejected += o.rejected;
    violations += o.violations;
    crashes += o.crashes;
  }
};

// Runs every case of `s` in child processes that report one outcome byte per case through
// a pipe. A child that dies costs one crash (the case after the last it reported), and a
// new child resumes after that case. Cases that are violations or crashes go to `notes`.
Counts sweep(const Subject& s, std::vector<std::string>* notes) {
  Counts c;
  c.cases = s.cases;
  size_t next = 0;
  while (next < s.cases) {
    int fds[2];
    if (pipe(fds) != 0) {
      notes->push_back(s.origin + ": pipe failed");
      ++c.crashes;
      return c;
    }
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      for (size_t i = next; i < s.cases; ++i) {
        const char outcome = s.run(i);
        if (write(fds[1], &outcome, 1) != 1) _exit(3);
      }
      _exit(0);
    }
    close(fds[1]);
    char buffer[4096];
    for (;;) {
      const ssize_t n = read(fds[0], buffer, sizeof(buffer));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      for (ssize_t k = 0; k < n; ++k, ++next) {
        if (buffer[k] == kValid) ++c.valid;
        if (buffer[k] == kRejected) ++c.rejected;
        if (buffer[k] == kViolation) {
          ++c.violations;
          notes->push_back(s.origin + ": " + s.describe(next) + ": contract violated");
        }
      }
    }
    close(fds[0]);
    int status = 0;
    const bool clean = pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!clean || next < s.cases) {
      ++c.crashes;
      notes->push_back(s.origin + ": " + (next < s.cases ? s.describe(next) : "after the last case") + ": crashed");
      ++next;
    }
  }
  return c;
}

TEST(VectorCorruption, EveryTruncationAndBitFlipOfEveryVectorDecodesOrIsRejected) {
  const std::vector<Subject> all = subjects();
  std::map<std::string, Counts> by_kind;
  std::vector<std::string> notes;
  for (const Subject& s : all) by_kind[s.kind].add(sweep(s, &notes));

  Counts total;
  std::printf("%-9s %8s %8s %9s %11s %8s\n", "kind", "cases", "valid", "rejected", "violations", "crashes");
  for (const char* kind : {"messages", "image", "can", "usb", "uart"}) {
    const Counts& c = by_kind[kind];
    std::printf("%-9s %8zu %8zu %9zu %11zu %8zu\n", kind, c.cases, c.valid, c.rejected, c.violations, c.crashes);
    total.add(c);
    EXPECT_GT(c.cases, 0u) << kind;
    EXPECT_GT(c.rejected, 0u) << kind;
    EXPECT_EQ(c.valid + c.rejected + c.violations + c.crashes, c.cases) << kind;
  }
  std::printf("%-9s %8zu %8zu %9zu %11zu %8zu\n", "total", total.cases, total.valid, total.rejected, total.violations,
              total.crashes);
  EXPECT_EQ(by_kind.size(), 5u);
  EXPECT_EQ(total.crashes, 0u);
  EXPECT_EQ(total.violations, 0u);
  for (size_t i = 0; i < notes.size() && i < 20; ++i) ADD_FAILURE() << notes[i];
  // Flips in free-valued fields (times, counters, chunk data) decode to other valid messages.
  EXPECT_GT(by_kind["messages"].valid, 0u);
}

// Several bytes of a vector changed at once (each XOR a non-zero mask), then maybe cut:
// damage a single flip does not model, such as a burst on the wire.
Bytes random_damage(Bytes bytes) {
  const size_t n = bytes.size();
  const auto count = *rc::gen::inRange<size_t>(2, 17);
  const auto at = *rc::gen::container<std::vector<size_t>>(count, rc::gen::inRange<size_t>(0, n));
  const auto masks = *rc::gen::container<std::vector<int>>(count, rc::gen::inRange<int>(1, 256));
  for (size_t i = 0; i < count; ++i) bytes[at[i]] ^= static_cast<uint8_t>(masks[i]);
  if (*rc::gen::weightedElement<bool>({{3, false}, {1, true}})) bytes.resize(*rc::gen::inRange<size_t>(0, n + 1));
  return bytes;
}

TEST(VectorCorruption, RandomMultiByteDamageOfEveryVectorDecodesOrIsRejected) {
  std::map<std::string, size_t> checked;
  size_t total = 0;
  for (const Subject& s : subjects()) {
    if (s.bytes.empty()) continue;  // the empty record: nothing to damage
    const bool ok = rc::check(s.origin, [&] {
      const Bytes damaged = random_damage(s.bytes);
      ++checked[s.kind];
      ++total;
      RC_ASSERT(s.decode(damaged) != kViolation);
    });
    EXPECT_TRUE(ok) << s.origin;
  }
  std::printf("random multi-byte damage checked:");
  for (const auto& [kind, n] : checked) std::printf(" %s %zu,", kind.c_str(), n);
  std::printf(" total %zu\n", total);
  EXPECT_EQ(checked.size(), 5u);
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
