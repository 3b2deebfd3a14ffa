#include "tetrapulse/host/link.hpp"

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::host {

using protocol::ByteView;
using protocol::Message;

int64_t Link::now_ns() const { return monotonic_now_ns(); }

HostResult<void> Link::send(const Message& message) {
  uint8_t buffer[protocol::kMaxMessageSize];
  protocol::ByteWriter writer(buffer, sizeof(buffer));
  const protocol::Status encoded = protocol::encode(message, writer);
  if (!encoded) {
    return host_error(HostErrorKind::kBadInput, name_,
                      fmt::format("{}: cannot encode: {}", protocol::message_name(message.type()),
                                  protocol::error_name(encoded.error())),
                      encoded.error());
  }
  auto sent = send_bytes(writer.view());
  if (sent) ++counters_.sent;
  return sent;
}

HostResult<std::optional<ReceivedMessage>> Link::next_from_transport(int64_t deadline_ns) {
  for (;;) {
    const int64_t remaining = deadline_ns - now_ns();
    if (remaining <= 0) return std::nullopt;
    auto raw = receive_bytes(remaining);
    if (!raw) return tl::unexpected(raw.error());
    if (!raw->has_value()) continue;  // the deadline check above ends the wait
    const RawMessage& r = **raw;
    const protocol::Result<Message> decoded = protocol::decode(ByteView{r.bytes.data(), r.bytes.size()});
    if (!decoded) {
      ++counters_.malformed;  // SPEC.md §3: a host drops what does not decode
      continue;
    }
    ++counters_.received;
    return ReceivedMessage{*decoded, r.received_ns, r.source_node};
  }
}

void Link::queue(ReceivedMessage message) {
  if (queued_.size() >= kMaxQueued) {
    queued_.pop_front();
    ++counters_.unmatched;
  }
  queued_.push_back(std::move(message));
}

HostResult<ReceivedMessage> Link::receive(std::chrono::milliseconds timeout) {
  if (!queued_.empty()) {
    ReceivedMessage m = std::move(queued_.front());
    queued_.pop_front();
    return m;
  }
  const int64_t timeout_ns = std::chrono::nanoseconds(timeout).count();
  auto next = next_from_transport(now_ns() + timeout_ns);
  if (!next) return tl::unexpected(next.error());
  if (!next->has_value()) {
    return host_error(HostErrorKind::kTimeout, name_, fmt::format("no message within {} ms{}", timeout.count(), silence_hint()),
                      protocol::Error::kTimeout);
  }
  return std::move(**next);
}

HostResult<ReceivedMessage> Link::request(const protocol::Body& body, std::chrono::milliseconds timeout) {
  Message message{take_seq(), body};
  const char* what = protocol::message_name(message.type());
  auto sent = send(message);
  if (!sent) {
    HostError e = sent.error();
    e.message = fmt::format("{}: {}", what, e.message);
    return tl::unexpected(e);
  }
  const int64_t deadline = now_ns() + std::chrono::nanoseconds(timeout).count();
  for (;;) {
    auto next = next_from_transport(deadline);
    if (!next) {
      HostError e = next.error();
      e.message = fmt::format("{}: {}", what, e.message);
      return tl::unexpected(e);
    }
    if (!next->has_value()) {
      return host_error(HostErrorKind::kTimeout, name_, fmt::format("{}: no answer within {} ms{}", what, timeout.count(), silence_hint()),
                        protocol::Error::kTimeout);
    }
    ReceivedMessage& m = **next;
    if (protocol::is_response(m.message.type()) && m.message.seq == message.seq) return std::move(m);
    if (protocol::is_response(m.message.type())) {
      ++counters_.unmatched;  // a late answer to an earlier request
      continue;
    }
    queue(std::move(m));
  }
}

}  // namespace tetrapulse::host
