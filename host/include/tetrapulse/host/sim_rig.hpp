#pragma once
// The virtual rig run by the real host code: one simulated board per target of a scenario
// (firmware/boards/sim, the boards sim's FirmwareBoardEmitter runs), each
//  - configured through host::Board over a SimLink with its targets.yaml codes, time base
//    and modulation (target_board_config.hpp);
//  - synchronised by the host's sync master over simulated wiring: boards with GPIO sync
//    hang on a trigger line that GpioSync drives at the scenario's frames (pulse k rises at
//    rig time frames.start_ns + k * frames.period_ns and lasts frames.exposure_ns), with
//    coarse time (FollowUp) once a second over each board's link; boards with CAN sync
//    hear CanSync's Sync/FollowUp on a simulated bus; free-running boards get nothing.
// The two settings not from targets.yaml are the simulation's: the epoch is shifted by the
// board's clock offset (sim::firmware_board_epoch_ns) and sync loss disconnects a board.
// Timing (power-up lead-in, sync rate, CAN latency, seed) follows
// sim::FirmwareEmitterOptions, so the boards receive what FirmwareBoardEmitter gives them.
// Times are integer ns of rig time.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/can_sync.hpp"
#include "tetrapulse/host/exposure.hpp"
#include "tetrapulse/host/gpio_sync.hpp"
#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/sim/dataset_simulation.hpp"
#include "tetrapulse/sim/firmware_board_emitter.hpp"
#include "tetrapulse/sim/scenario.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::host {

class SimCanBus;

class HostSyncedRig {
 public:
  // Powers the boards up and configures them; an error names the board that refused.
  static HostResult<std::shared_ptr<HostSyncedRig>> create(const sim::Scenario& scenario,
                                                           const sim::FirmwareEmitterOptions& options = {});
  ~HostSyncedRig();
  HostSyncedRig(const HostSyncedRig&) = delete;
  HostSyncedRig& operator=(const HostSyncedRig&) = delete;

  // Runs the sync masters and every board up to rig time t (at least; never back).
  void run_until(int64_t rig_ns);

  size_t boards() const { return sims_.size(); }
  const sim_board::SimBoard& board(size_t index) const { return *sims_[index]; }
  Board& host_board(size_t index) { return *boards_[index]; }
  // The trigger's exposures so far, numbered as the scenario's frames (frame 0 at
  // frames.start_ns; the lead-in's pulses before it are left out).
  const std::vector<Exposure>& exposures() const { return exposures_; }
  // Exposures triggered so far, the forgotten ones included.
  uint64_t exposure_count() const { return forgotten_exposures_ + exposures_.size(); }
  // Long runs: exposures and the boards' LED changes before rig time t are dropped, so
  // memory stays bounded (exposures() and the boards' logs then start there).
  void forget_before(int64_t rig_ns);
  // CAN Sync/FollowUp pairs sent so far.
  uint64_t can_syncs() const { return can_syncs_; }
  // The first sync master error, if any (the rig stops syncing then).
  const std::optional<HostError>& failure() const { return failure_; }

 private:
  HostSyncedRig() = default;
  HostResult<void> set_up(const sim::Scenario& scenario, const sim::FirmwareEmitterOptions& options);
  // Everything but trigger pulses: CAN syncs, coarse time, the boards, up to t.
  void run_others_until(int64_t rig_ns);

  std::vector<std::shared_ptr<sim_board::SimBoard>> sims_;
  std::vector<std::unique_ptr<Board>> boards_;
  std::vector<size_t> gpio_boards_;
  // CAN
  SimCanBus* bus_ = nullptr;  // owned by can_
  std::unique_ptr<CanSync> can_;
  int64_t can_period_ns_ = 0;
  int64_t next_can_ns_ = 0;
  uint64_t can_syncs_ = 0;
  // GPIO
  std::unique_ptr<GpioSync> trigger_;
  int64_t pulse_period_ns_ = 0;
  int64_t next_pulse_ns_ = 0;
  int64_t frame0_ns_ = 0;
  int64_t next_coarse_ns_ = 0;
  uint16_t coarse_seq_ = 0;
  std::vector<Exposure> exposures_;
  uint64_t forgotten_exposures_ = 0;
  std::optional<HostError> failure_;
};

// Each target's light from the rig's boards, for sim::build_scene / sim::simulate_dataset
// (the factory shares the rig; it runs the rig as far as the renderer asks).
sim::BoardEmitterFactory host_board_emitters(std::shared_ptr<HostSyncedRig> rig);

// sim::simulate_dataset (same files, same options) with every target's board configured
// and synchronised by the host code above rather than by sim's FirmwareBoardEmitter.
// `options.board` is ignored. Errors name the board, or the dataset file.
HostResult<sim::SimulationSummary> simulate_with_host_boards(const sim::Scenario& scenario,
                                                             sim::SimulationOptions options,
                                                             const sim::FirmwareEmitterOptions& boards = {});

}  // namespace tetrapulse::host
