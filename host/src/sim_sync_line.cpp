#include "tetrapulse/host/sim_sync_line.hpp"

namespace tetrapulse::host {

void SimSyncLine::attach(std::shared_ptr<sim_board::SimBoard> board, std::function<bool(int64_t)> connected) {
  inputs_.push_back(Input{std::move(board), std::move(connected)});
}

bool SimSyncLine::do_sleep_until(int64_t rig_ns, const std::atomic<bool>& stop) {
  if (stop.load()) return false;
  if (rig_ns > now_) {
    run_until_(rig_ns);
    now_ = rig_ns;
  }
  return true;
}

HostResult<int64_t> SimSyncLine::do_set(bool active) {
  if (active && !active_) {
    for (Input& in : inputs_) {
      if (in.connected(now_)) in.board->sync_edge(now_);
    }
  }
  active_ = active;
  return now_;
}

HostResult<std::vector<GpioSyncLine::Edge>> SimSyncLine::do_wait_edges(int64_t timeout_ns) {
  if (timeout_ns > 0) run_until_(now_ + timeout_ns);
  now_ += timeout_ns > 0 ? timeout_ns : 0;
  return std::vector<Edge>{};
}

}  // namespace tetrapulse::host
