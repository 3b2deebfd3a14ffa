// Round trips for every message on every transport, one parameterised test: each golden
// message (vectors/messages) and random messages of every type go through CAN (sender ->
// receiver, the identifier's fields and the receiver's filters checked), USB bulk framing,
// USB control (MESSAGE_OUT and MESSAGE_IN data stages) and UART framing, and decode back to
// an equal message.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <tl/expected.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "golden_messages.hpp"
#include "message_generators.hpp"
#include "message_testing.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_control.hpp"
#include "transport_testing.hpp"

namespace tetrapulse::protocol::testing {
namespace {

using Bytes = std::vector<uint8_t>;
using Delivered = tl::expected<Bytes, std::string>;

Delivered fail(const std::string& why) { return tl::make_unexpected(why); }
Bytes bytes_of(ByteView v) { return Bytes(v.begin(), v.end()); }

// Who sends to whom on CAN.
struct CanRoute {
  uint8_t priority = kCanPriorityRequest;
  uint8_t source = kCanHostNode;
  uint8_t destination = kCanBroadcastNode;
};

Delivered over_can(const Bytes& m, const CanRoute& route) {
  CanTransferSender sender(route.source);
  std::vector<CanFrame> frames;
  const Status sent = sender.send(route.priority, route.destination, view(m), [&](const CanFrame& f) {
    frames.push_back(f);
    return Status{};
  });
  if (!sent) return fail(std::string("CAN send: ") + error_name(sent.error()));
  if (frames.size() != can_frame_count(m.size())) return fail("CAN: " + std::to_string(frames.size()) + " frames");
  // The receiving node: the destination, or any board for a broadcast.
  const CanNodeFilters filters = can_node_filters(route.destination == kCanBroadcastNode ? 7 : route.destination);
  CanReceiveSession session;
  CanTransferReceiver rx(&session, 1);
  for (size_t i = 0; i < frames.size(); ++i) {
    const Result<CanId> id = unpack_can_id(frames[i].id);
    if (!id || id->type != m[1] || id->priority != route.priority || id->source != route.source ||
        id->destination != route.destination) {
      return fail("CAN frame " + std::to_string(i) + ": identifier " + std::to_string(frames[i].id));
    }
    if (!can_filter_matches(filters.addressed, frames[i].id) && !can_filter_matches(filters.broadcast, frames[i].id)) {
      return fail("CAN frame " + std::to_string(i) + ": the receiver's filters refuse it");
    }
    const CanReceiveOutcome out = rx.accept(frames[i], static_cast<int64_t>(i) * 100'000);
    const bool last = i + 1 == frames.size();
    if (out.verdict != (last ? CanFrameVerdict::kComplete : CanFrameVerdict::kPending)) {
      return fail("CAN frame " + std::to_string(i) + ": " + can_fault_name(out.fault));
    }
    if (!last) continue;
    if (out.transfer.id != *id || out.transfer.timestamp_ns != 0) return fail("CAN: transfer identifier or time");
    return bytes_of(out.transfer.message);
  }
  return fail("CAN: no frames");
}

// Packets into a receiver that must say nothing until the last one completes the message.
template <class Receiver>
Delivered through_packets(Receiver& rx, const std::vector<Bytes>& packets, const std::string& what) {
  for (size_t i = 0; i < packets.size(); ++i) {
    const ReceiveEvent e = rx.push_packet(view(packets[i]));
    const bool last = i + 1 == packets.size();
    if (e.kind != (last ? ReceiveKind::kMessage : ReceiveKind::kNothing)) {
      return fail(what + " packet " + std::to_string(i) + ": " + error_name(e.error));
    }
    if (last) return bytes_of(e.message);
  }
  return fail(what + ": no packets");
}

Delivered over_usb_bulk(const Bytes& m) {
  Bytes transfer(kUsbBulkMaxTransfer);
  const Result<size_t> n = encode_usb_bulk_frame(view(m), transfer.data(), transfer.size());
  if (!n) return fail(std::string("USB bulk encode: ") + error_name(n.error()));
  transfer.resize(*n);
  const auto packets = usb_packets(transfer);
  if (packets.size() != usb_bulk_packet_count(transfer.size())) return fail("USB bulk: packet count");
  UsbBulkFrameReceiver rx;
  return through_packets(rx, packets, "USB bulk");
}

// Host to device: MESSAGE_OUT with wLength = the message size, the data stage in packets.
Delivered over_usb_message_out(const Bytes& m) {
  UsbMessageOutReceiver rx;
  const Status setup = rx.begin(static_cast<uint16_t>(m.size()));
  if (!setup) return fail(std::string("MESSAGE_OUT setup: ") + error_name(setup.error()));
  return through_packets(rx, usb_packets(m, false), "MESSAGE_OUT");  // exactly wLength bytes: no ZLP
}

// Device to host: MESSAGE_IN with wLength = kMaxMessageSize; the host takes packets until
// a short one or wLength bytes.
Delivered over_usb_message_in(const Bytes& m) {
  constexpr auto kWLength = static_cast<uint16_t>(kMaxMessageSize);
  const Status s = check_usb_message_in(kWLength, m.size());
  if (!s) return fail(std::string("MESSAGE_IN: ") + error_name(s.error()));
  Bytes received;
  for (const Bytes& packet : usb_packets(m, usb_control_in_needs_zlp(m.size(), kWLength))) {
    received.insert(received.end(), packet.begin(), packet.end());
    if (packet.size() < kUsbMaxPacketSize || received.size() == kWLength) return received;
  }
  return received;
}

Delivered over_uart(const Bytes& m) {
  Bytes frame(uart_max_frame_size(m.size()));
  const Result<size_t> n = encode_uart_frame(view(m), frame.data(), frame.size());
  if (!n) return fail(std::string("UART encode: ") + error_name(n.error()));
  frame.resize(*n);
  UartFrameDecoder decoder;
  size_t used = 0;
  const ReceiveEvent e = decoder.feed(view(frame), &used);
  if (e.kind != ReceiveKind::kMessage || used != frame.size()) return fail(std::string("UART: ") + error_name(e.error));
  return bytes_of(e.message);
}

enum class Transport { kCan, kUsbBulk, kUsbMessageOut, kUsbMessageIn, kUart };

const char* transport_name(Transport t) {
  switch (t) {
    case Transport::kCan: return "can";
    case Transport::kUsbBulk: return "usb_bulk";
    case Transport::kUsbMessageOut: return "usb_message_out";
    case Transport::kUsbMessageIn: return "usb_message_in";
    case Transport::kUart: return "uart";
  }
  return "?";
}

// Sends the encoding of `m` over `transport`; an empty result means it delivered bytes that
// decode to a message equal to `m`, else it says what went wrong.
std::string round_trip(const Message& m, Transport transport, const CanRoute& route) {
  const Bytes bytes = encode_bytes(m);
  if (bytes.empty()) return "does not encode";
  Delivered delivered = fail("no transport");
  switch (transport) {
    case Transport::kCan: delivered = over_can(bytes, route); break;
    case Transport::kUsbBulk: delivered = over_usb_bulk(bytes); break;
    case Transport::kUsbMessageOut: delivered = over_usb_message_out(bytes); break;
    case Transport::kUsbMessageIn: delivered = over_usb_message_in(bytes); break;
    case Transport::kUart: delivered = over_uart(bytes); break;
  }
  if (!delivered) return delivered.error();
  const auto decoded = decode(view(*delivered));
  if (!decoded) return std::string("delivered bytes decode to ") + error_name(decoded.error());
  if (text(*decoded) != text(m)) return "delivered " + text(*decoded);
  return {};
}

// The CAN route of a message between the host and board 3: requests to the board, responses
// from it, time sync broadcast.
CanRoute usual_route(const Message& m) {
  if (is_time_sync(m.type())) return CanRoute{kCanPrioritySync, kCanHostNode, kCanBroadcastNode};
  if (is_request(m.type())) return CanRoute{kCanPriorityRequest, kCanHostNode, 3};
  return CanRoute{kCanPriorityResponse, 3, kCanHostNode};
}

// One case per (transport, message type): every golden message of the type (vectors/messages)
// and random ones (every field anywhere in its range, any CAN route) arrive equal.
struct RoundTripCase {
  Transport transport;
  MessageType type;
};

void PrintTo(const RoundTripCase& c, std::ostream* os) {
  *os << message_name(c.type) << " over " << transport_name(c.transport);
}

std::vector<RoundTripCase> every_transport_and_type() {
  std::vector<RoundTripCase> cases;
  for (Transport t : {Transport::kCan, Transport::kUsbBulk, Transport::kUsbMessageOut, Transport::kUsbMessageIn,
                      Transport::kUart}) {
    for (MessageType type : body_types()) cases.push_back({t, type});
  }
  return cases;
}

std::string round_trip_case_name(const ::testing::TestParamInfo<RoundTripCase>& info) {
  return std::string(transport_name(info.param.transport)) + "_" + message_name(info.param.type);
}

class MessageOverTransport : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(MessageOverTransport, ArrivesEqual) {
  const Transport transport = GetParam().transport;
  const MessageType type = GetParam().type;
  size_t goldens = 0;
  for (const auto& [key, golden] : golden_messages()) {
    if (golden.type() != type) continue;
    ++goldens;
    EXPECT_EQ(round_trip(golden, transport, usual_route(golden)), "") << key;
  }
  EXPECT_GT(goldens, 0u) << "no golden " << message_name(type) << " in vectors/messages";
  const bool ok = rc::check(message_name(type), [transport, type](uint8_t seq) {
    const Message m{seq, *body_of_type(type)};
    RC_ASSERT(m.type() == type);
    const CanRoute route{*rc::gen::inRange<uint8_t>(0, kCanPriorityLowest + 1),
                         *rc::gen::inRange<uint8_t>(kCanHostNode, kCanLastBoardNode + 1),
                         *rc::gen::arbitrary<uint8_t>()};
    const std::string failure = round_trip(m, transport, route);
    if (!failure.empty()) RC_FAIL(failure);
  });
  EXPECT_TRUE(ok);
}

INSTANTIATE_TEST_SUITE_P(EveryMessage, MessageOverTransport, ::testing::ValuesIn(every_transport_and_type()),
                         round_trip_case_name);

}  // namespace
}  // namespace tetrapulse::protocol::testing
