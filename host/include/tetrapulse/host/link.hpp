#pragma once
// A link to one board (or, on CAN, to every board of a bus): sends protocol messages,
// receives them with a receive timestamp, and matches responses to requests by seq
// (protocol/SPEC.md §2.2). Transports (USB, CAN, serial, simulated) only move the bytes
// of whole messages; this class encodes, decodes, correlates and times out.
//
// Times: `received_ns` and timeouts are on the link's clock, now_ns(): CLOCK_MONOTONIC
// for real links (kernel receive timestamps where the transport has them, rig_clock.hpp),
// the simulated clock for SimLink. A Link is used from one thread at a time.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::host {

// The bytes of one message as a transport delivered them.
struct RawMessage {
  std::vector<uint8_t> bytes;
  int64_t received_ns = 0;
  uint8_t source_node = 0;  // CAN: the sender's node id; other transports: 0
};

struct ReceivedMessage {
  protocol::Message message;
  int64_t received_ns = 0;  // on the link's clock (see above)
  uint8_t source_node = 0;  // CAN: the sender's node id; other transports: 0
};

struct LinkCounters {
  uint32_t sent = 0;
  uint32_t received = 0;          // messages that decoded
  uint32_t malformed = 0;         // message bytes that did not decode (dropped)
  uint32_t transport_errors = 0;  // frames the transport dropped (bad CRC, COBS, CAN faults)
  uint32_t unmatched = 0;         // responses to no pending request, and overflowed queue entries
};

class Link {
 public:
  static constexpr std::chrono::milliseconds kDefaultTimeout{1000};  // SPEC.md §5.5
  static constexpr size_t kMaxQueued = 64;

  // `first_seq`: the seq of the first request (any value, SPEC.md §2.2; see CanLink::open).
  explicit Link(std::string name, uint8_t first_seq = 1) : name_(std::move(name)), next_seq_(first_seq) {}
  virtual ~Link() = default;
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  // "usb:0123ABCD", "can:vcan0:3", "serial:/dev/ttyUSB0", "sim:1": names the board in errors.
  const std::string& name() const { return name_; }

  // Encodes and sends one message as it is (its seq included).
  HostResult<void> send(const protocol::Message& message);
  // The next message that is not the answer to a request: queued ones first, then from the
  // transport. kTimeout when none arrives in time.
  HostResult<ReceivedMessage> receive(std::chrono::milliseconds timeout);
  // Sends `body` with a fresh seq and waits for the response carrying that seq (any response
  // type: the caller checks it, ErrorResponse included). Other messages that arrive meanwhile
  // are queued for receive().
  HostResult<ReceivedMessage> request(const protocol::Body& body,
                                      std::chrono::milliseconds timeout = kDefaultTimeout);

  // A fresh seq, for a request sent with send() whose answers the caller collects with
  // receive() (a CAN broadcast answered by every board).
  uint8_t take_seq() { return next_seq_++; }

  // The transport alone, without encoding or decoding: sends the bytes of one message
  // (3..320 bytes, framed as the transport frames them) and waits at most `timeout_ns`
  // for the bytes of one message (nullopt when none came). For diagnostics and tests.
  HostResult<void> send_raw(protocol::ByteView message) { return send_bytes(message); }
  HostResult<std::optional<RawMessage>> receive_raw(int64_t timeout_ns) { return receive_bytes(timeout_ns); }

  const LinkCounters& counters() const { return counters_; }
  // The clock of received_ns and of every timeout.
  virtual int64_t now_ns() const;

 protected:
  virtual HostResult<void> send_bytes(protocol::ByteView message) = 0;
  virtual HostResult<std::optional<RawMessage>> receive_bytes(int64_t timeout_ns) = 0;
  // Appended to "no answer within N ms": what the transport saw that may explain it.
  virtual std::string silence_hint() const { return {}; }

  LinkCounters counters_;

 private:
  // One decoded message from the transport within `deadline_ns`, or nullopt at the deadline.
  HostResult<std::optional<ReceivedMessage>> next_from_transport(int64_t deadline_ns);
  void queue(ReceivedMessage message);

  std::string name_;
  uint8_t next_seq_;
  std::deque<ReceivedMessage> queued_;
};

}  // namespace tetrapulse::host
