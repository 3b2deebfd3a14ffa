#pragma once
// An in-memory CAN bus for unit tests of CAN links and sync: ports that deliver to each
// other through acceptance filters, nodes (responders) that answer frames at once, error
// frames on demand and transmit timestamps like SocketCAN's. Single-threaded: a port's
// next() returns what is queued, or waits out its timeout when nothing is.
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/can_port.hpp"

namespace tetrapulse::host::testing {

class FakeCanBus {
 public:
  using Node = std::function<std::vector<protocol::CanFrame>(const protocol::CanFrame&, int64_t now_ns)>;

  explicit FakeCanBus(std::string interface_name = "vcan0") : name_(std::move(interface_name)) {}

  // A port on this bus (it must not outlive the bus).
  std::unique_ptr<CanPort> open(const SocketCanOptions& options = {});
  // A node that sees every frame on the bus and answers at once.
  void attach(Node node) { nodes_.push_back(std::move(node)); }
  // An error frame (linux/can/error.h class bits) reaching every port.
  void raise_error(uint32_t error_class, const std::array<uint8_t, 8>& data = {});
  // Every data frame that went on the bus, in order.
  const std::vector<protocol::CanFrame>& frames() const { return log_; }
  // Frames lost on the way to nodes when this returns true (a lossy bus).
  void lose_when(std::function<bool(const protocol::CanFrame&)> lose) { lose_ = std::move(lose); }

 private:
  class Port;
  friend class Port;
  void transmit(Port* from, const protocol::CanFrame& frame);
  void deliver(Port* from, const protocol::CanFrame& frame, int64_t now_ns);

  std::string name_;
  std::vector<Port*> ports_;
  std::vector<Node> nodes_;
  std::vector<protocol::CanFrame> log_;
  std::function<bool(const protocol::CanFrame&)> lose_;
};

}  // namespace tetrapulse::host::testing
