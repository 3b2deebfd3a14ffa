#pragma once
// A camera trigger line of the virtual rig as a GpioSyncLine: GpioSync drives it in
// simulated rig time, and every active edge reaches the sync input of each attached
// simulated board (firmware/boards/sim) that is connected then. Waiting lets the rest of
// the rig run: sleep_until(t) calls `run_until(t)` (the boards, other sync traffic) first.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/gpio_sync.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::host {

class SimSyncLine final : public GpioSyncLine {
 public:
  SimSyncLine(std::string name, int64_t start_ns, std::function<void(int64_t)> run_until)
      : name_(std::move(name)), now_(start_ns), run_until_(std::move(run_until)) {}

  // `connected(t)`: whether the board's sync input is wired at rig time t.
  void attach(std::shared_ptr<sim_board::SimBoard> board, std::function<bool(int64_t)> connected);

 private:
  const std::string& do_name() const override { return name_; }
  int64_t do_now() const override { return now_; }
  bool do_sleep_until(int64_t rig_ns, const std::atomic<bool>& stop) override;
  HostResult<int64_t> do_set(bool active) override;
  // A trigger line is an output: it never reports edges.
  HostResult<std::vector<Edge>> do_wait_edges(int64_t timeout_ns) override;

  struct Input {
    std::shared_ptr<sim_board::SimBoard> board;
    std::function<bool(int64_t)> connected;
  };
  std::string name_;
  int64_t now_;
  std::function<void(int64_t)> run_until_;
  bool active_ = false;
  std::vector<Input> inputs_;
};

}  // namespace tetrapulse::host
