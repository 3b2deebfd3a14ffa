#pragma once
// A link that carries protocol messages (CAN, USB, UART): messages come in with the
// local tick of their reception, responses go back the way the request came.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

enum class LinkKind : uint8_t { kCan, kUsb, kUart };

// Whom a response goes to, on the link its request came by.
struct ReplyPath {
  uint8_t peer = 0;   // CAN: the requester's node id; USB: kUsbBulkPath or kUsbControlPath; UART: 0
  uint8_t local = 0;  // CAN: the node id the request was addressed to (the answer comes from it)
};

class MessageLink {
 public:
  LinkKind kind() const { return do_kind(); }
  // Sends one whole message (3..320 bytes). kBusy when the link cannot take it now.
  protocol::Status send(const ReplyPath& to, protocol::ByteView message) { return do_send(to, message); }

 protected:
  ~MessageLink() = default;

 private:
  virtual LinkKind do_kind() const = 0;
  virtual protocol::Status do_send(const ReplyPath& to, protocol::ByteView message) = 0;
};

// One message as received, before decoding.
struct ReceivedMessage {
  protocol::ByteView bytes;     // the whole message; valid only during the call
  Tick rx_tick = 0;             // local tick of reception (CAN: the transfer's first frame)
  MessageLink* link = nullptr;  // where it came from (and where its answer goes)
  ReplyPath reply;
};

// Takes received messages (Firmware implements it).
class MessageSink {
 public:
  void on_message(const ReceivedMessage& message) { do_on_message(message); }

 protected:
  ~MessageSink() = default;

 private:
  virtual void do_on_message(const ReceivedMessage& message) = 0;
};

}  // namespace tetrapulse::fw
