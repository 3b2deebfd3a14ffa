#include "tetrapulse/host/sim_board_link.hpp"

#include <deque>

#include <fmt/format.h>

#include "tetrapulse/sim_board/host_port.hpp"

namespace tetrapulse::host {
namespace {

class SimBoardUsbPort : public SimBoardPort {
 public:
  explicit SimBoardUsbPort(std::shared_ptr<sim_board::SimBoard> board) : board_(std::move(board)), port_(*board_) {}

  void deliver(protocol::ByteView message) override { port_.send(fw::LinkKind::kUsb, message, board_->now()); }
  void advance(int64_t ns) override {
    board_->advance_to(board_->now() + ns);
    collect();
  }
  std::optional<std::vector<uint8_t>> take_sent() override {
    collect();
    if (sent_.empty()) return std::nullopt;
    std::vector<uint8_t> m = std::move(sent_.front());
    sent_.pop_front();
    return m;
  }
  int64_t now_ns() const override { return board_->now(); }

 private:
  void collect() {
    for (auto& m : port_.receive(fw::LinkKind::kUsb)) sent_.push_back(std::move(m));
  }

  std::shared_ptr<sim_board::SimBoard> board_;
  sim_board::HostPort port_;
  std::deque<std::vector<uint8_t>> sent_;
};

}  // namespace

std::shared_ptr<SimBoardPort> sim_board_port(std::shared_ptr<sim_board::SimBoard> board) {
  return std::make_shared<SimBoardUsbPort>(std::move(board));
}

HostResult<std::unique_ptr<Link>> open_sim_link(const BoardAddress& address) {
  if (address.kind != BoardAddress::Kind::kSim) {
    return host_error(HostErrorKind::kBadInput, address.text(), "not a simulated board");
  }
  sim_board::SimBoardOptions options;
  options.node_id = address.node;
  options.serial = {'S', 'I', 'M', 0, 0, 0, 0, 0, 0, 0, 0, address.node};
  auto board = std::make_shared<sim_board::SimBoard>(options);
  return std::unique_ptr<Link>(std::make_unique<SimLink>(address.text(), sim_board_port(board)));
}

}  // namespace tetrapulse::host
