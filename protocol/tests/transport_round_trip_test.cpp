// Round trips for every message on every transport: each golden message (vectors/messages)
// and random messages of every type go through CAN (sender -> receiver, the identifier's
// type field checked), USB bulk framing, USB control (MESSAGE_OUT and MESSAGE_IN data
// stages) and UART framing, and decode back to an equal message.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <string>
#include <vector>

#include "message_generators.hpp"
#include "message_testing.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_control.hpp"
#include "transport_testing.hpp"
#include "vector_cases.hpp"

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

// Sends the encoding of `m` over every transport; an empty result means every one gave
// back a message equal to `m`, else it names the transport and what went wrong.
std::string round_trip_everywhere(const Message& m, const CanRoute& route) {
  const Bytes bytes = encode_bytes(m);
  if (bytes.empty()) return "does not encode";
  const std::pair<const char*, Delivered> results[] = {
      {"can", over_can(bytes, route)},
      {"usb bulk", over_usb_bulk(bytes)},
      {"usb MESSAGE_OUT", over_usb_message_out(bytes)},
      {"usb MESSAGE_IN", over_usb_message_in(bytes)},
      {"uart", over_uart(bytes)},
  };
  for (const auto& [transport, delivered] : results) {
    if (!delivered) return std::string(transport) + ": " + delivered.error();
    const auto decoded = decode(view(*delivered));
    if (!decoded) return std::string(transport) + ": delivered bytes decode to " + error_name(decoded.error());
    if (text(*decoded) != text(m)) return std::string(transport) + ": delivered " + text(*decoded);
  }
  return {};
}

class GoldenMessageOnEveryTransport : public ::testing::TestWithParam<VectorCase> {};

TEST_P(GoldenMessageOnEveryTransport, ArrivesEqual) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  const auto golden = decode(view(c.record.bytes));
  ASSERT_TRUE(golden.ok()) << c.record.origin << ": " << error_name(golden.error());
  // Requests from the host to board 3, everything else from board 3 to the host; time sync broadcast.
  CanRoute route{kCanPriorityRequest, kCanHostNode, 3};
  if (!is_request(golden->type())) route = CanRoute{kCanPriorityResponse, 3, kCanHostNode};
  if (golden->get<Sync>() != nullptr || golden->get<FollowUp>() != nullptr) {
    route = CanRoute{kCanPrioritySync, kCanHostNode, kCanBroadcastNode};
  }
  EXPECT_EQ(round_trip_everywhere(*golden, route), "") << c.record.origin;
}

INSTANTIATE_TEST_SUITE_P(Vectors, GoldenMessageOnEveryTransport, ::testing::ValuesIn(vector_cases("messages")),
                         case_name);

template <class T>
class RandomMessageOnEveryTransport : public ::testing::Test {};
TYPED_TEST_SUITE(RandomMessageOnEveryTransport, BodyTypes, BodyTypeName);

TYPED_TEST(RandomMessageOnEveryTransport, ArrivesEqual) {
  const bool ok = rc::check(message_name(TypeParam::kType), [](uint8_t seq, const TypeParam& body) {
    const CanRoute route{*rc::gen::inRange<uint8_t>(0, kCanPriorityLowest + 1),
                         *rc::gen::inRange<uint8_t>(kCanHostNode, kCanLastBoardNode + 1),
                         *rc::gen::arbitrary<uint8_t>()};
    const std::string failure = round_trip_everywhere(Message{seq, body}, route);
    if (!failure.empty()) RC_FAIL(failure);
  });
  EXPECT_TRUE(ok);
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
