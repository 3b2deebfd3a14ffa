#pragma once
// One board, over any link: the requests of protocol/SPEC.md §2.3 as calls. Every call
// returns the board's answer or a HostError naming the board and the request
// ("can:vcan0:3: set_config: board refused: not_supported").
#include <chrono>
#include <cstdint>
#include <memory>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/host/link.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::host {

struct BoardTimeouts {
  std::chrono::milliseconds request{1000};  // SPEC.md §5.5
  // Requests that write flash (PersistConfig, FactoryReset, UpdateBegin erases a slot,
  // UpdateVerify reads it back) may take longer on a microcontroller.
  std::chrono::milliseconds flash{5000};
};

class Board {
 public:
  explicit Board(std::unique_ptr<Link> link, BoardTimeouts timeouts = {})
      : link_(std::move(link)), timeouts_(timeouts) {}

  const std::string& name() const { return link_->name(); }
  Link& link() { return *link_; }
  const BoardTimeouts& timeouts() const { return timeouts_; }

  HostResult<protocol::Info> info();
  HostResult<protocol::Config> config();
  // Replaces the running configuration (SetConfig); persist() stores it.
  HostResult<void> configure(const protocol::Config& config);
  HostResult<void> identify(protocol::IdentifyPattern pattern, uint16_t duration_ms);
  HostResult<void> persist();
  HostResult<void> factory_reset();
  // The board acknowledges, then resets (SPEC.md §2.3).
  HostResult<void> reboot(protocol::RebootMode mode);
  HostResult<protocol::StatusReport> status();
  HostResult<protocol::LedLog> led_log(uint32_t first);

  // Any request answered by Ack: the Ack's value (SPEC.md §2.6).
  HostResult<uint32_t> command(const protocol::Body& request, std::chrono::milliseconds timeout);

 private:
  template <class Response>
  HostResult<Response> ask(const protocol::Body& request, std::chrono::milliseconds timeout);

  std::unique_ptr<Link> link_;
  BoardTimeouts timeouts_;
};

// The error for an answer that is not the expected response: kBoardRefused for an
// ErrorResponse (with the board's error), kMalformed for anything else.
HostError unexpected_answer(const std::string& board, protocol::MessageType request, const protocol::Message& answer);

}  // namespace tetrapulse::host
