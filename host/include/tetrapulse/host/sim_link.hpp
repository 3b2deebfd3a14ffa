#pragma once
// A link to a board of the virtual rig, in the same process (firmware/boards/sim).
//
// The board is reached through SimBoardPort, the whole of what the host needs from a
// simulated board: take a message, let simulated time run, hand over what it sent.
// Timeouts and receive timestamps are in the board's simulated time, so a SimLink
// conversation is deterministic and never waits on the wall clock.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tetrapulse/host/link.hpp"

namespace tetrapulse::host {

class SimBoardPort {
 public:
  virtual ~SimBoardPort() = default;
  // One encoded message arriving at the board, as if on its link, at the current simulated time.
  virtual void deliver(protocol::ByteView message) = 0;
  // Lets simulated time run by `ns` (> 0): the board handles what it was given.
  virtual void advance(int64_t ns) = 0;
  // The oldest message the board sent and the host has not taken yet.
  virtual std::optional<std::vector<uint8_t>> take_sent() = 0;
  // Simulated time now, ns.
  virtual int64_t now_ns() const = 0;
};

class SimLink : public Link {
 public:
  // Simulated time advances in steps of `step_ns` while the host waits for an answer.
  static constexpr int64_t kDefaultStepNs = 100'000;

  SimLink(std::string name, std::shared_ptr<SimBoardPort> board, int64_t step_ns = kDefaultStepNs)
      : Link(std::move(name)), board_(std::move(board)), step_ns_(step_ns) {}

  int64_t now_ns() const override { return board_->now_ns(); }
  SimBoardPort& board() { return *board_; }

 protected:
  HostResult<void> send_bytes(protocol::ByteView message) override;
  HostResult<std::optional<RawMessage>> receive_bytes(int64_t timeout_ns) override;

 private:
  std::shared_ptr<SimBoardPort> board_;
  int64_t step_ns_;
};

}  // namespace tetrapulse::host
