#include "responder_sim_port.hpp"

namespace tetrapulse::host::testing {

void ResponderSimPort::deliver(protocol::ByteView message) {
  auto reply = responder_.answer(message, now_ns_);
  if (!reply) return;
  if (lose_) {
    const protocol::Result<protocol::Message> m = protocol::decode(protocol::ByteView{reply->data(), reply->size()});
    if (m && lose_(*m)) {
      ++lost_;
      return;
    }
  }
  pending_.emplace_back(now_ns_ + latency_ns_, std::move(*reply));
}

void ResponderSimPort::advance(int64_t ns) {
  now_ns_ += ns;
  while (!pending_.empty() && pending_.front().first <= now_ns_) {
    sent_.push_back(std::move(pending_.front().second));
    pending_.pop_front();
  }
}

std::optional<std::vector<uint8_t>> ResponderSimPort::take_sent() {
  if (sent_.empty()) return std::nullopt;
  std::vector<uint8_t> out = std::move(sent_.front());
  sent_.pop_front();
  return out;
}

}  // namespace tetrapulse::host::testing
