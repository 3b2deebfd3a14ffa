#include "tetrapulse/host/sim_link.hpp"

#include <algorithm>

namespace tetrapulse::host {

HostResult<void> SimLink::send_bytes(protocol::ByteView message) {
  board_->deliver(message);
  return {};
}

HostResult<std::optional<RawMessage>> SimLink::receive_bytes(int64_t timeout_ns) {
  const int64_t deadline = board_->now_ns() + timeout_ns;
  for (;;) {
    if (auto sent = board_->take_sent()) return RawMessage{std::move(*sent), board_->now_ns(), 0};
    const int64_t left = deadline - board_->now_ns();
    if (left <= 0) return std::nullopt;
    board_->advance(std::min(step_ns_, left));
  }
}

}  // namespace tetrapulse::host
