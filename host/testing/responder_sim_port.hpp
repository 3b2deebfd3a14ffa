#pragma once
// A BoardResponder behind the SimBoardPort seam: answers after `latency_ns` of simulated
// time, and can lose answers on purpose (a lost Ack on a lossy link).
#include <deque>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "board_responder.hpp"
#include "tetrapulse/host/sim_link.hpp"

namespace tetrapulse::host::testing {

class ResponderSimPort : public SimBoardPort {
 public:
  explicit ResponderSimPort(ResponderIdentity identity = {}, int64_t latency_ns = 300'000)
      : responder_(identity), latency_ns_(latency_ns) {}

  void deliver(protocol::ByteView message) override;
  void advance(int64_t ns) override;
  std::optional<std::vector<uint8_t>> take_sent() override;
  int64_t now_ns() const override { return now_ns_; }

  BoardResponder& responder() { return responder_; }
  // Called with each answer before it is sent; returning true loses it.
  void lose_answers_when(std::function<bool(const protocol::Message&)> lose) { lose_ = std::move(lose); }
  uint32_t answers_lost() const { return lost_; }

 private:
  BoardResponder responder_;
  int64_t latency_ns_;
  int64_t now_ns_ = 1'000'000'000;
  std::deque<std::pair<int64_t, std::vector<uint8_t>>> pending_;  // (due time, bytes)
  std::deque<std::vector<uint8_t>> sent_;
  std::function<bool(const protocol::Message&)> lose_;
  uint32_t lost_ = 0;
};

}  // namespace tetrapulse::host::testing
