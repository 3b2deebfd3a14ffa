#pragma once
// A target's light from a simulated board running the real firmware (firmware/boards/sim):
// the board is configured through its command handler with the target's codes and time
// base, its crystal runs off by the scenario's clock_ppm, and it is synchronized as the
// scenario says: GPIO edges at every exposure start of the camera (edge k = frame k,
// numbered from a coarse-time FollowUp over USB every second), CAN Sync/FollowUp at
// 10 Hz with 0..50 us reception latency, or nothing (free-running). The emission over a
// window is the board's logged LED duty integrated over it.
//
// The camera's strobe and the CAN sync run for `lead_in_ns` before frame 0, so the boards
// are locked when recording starts. A board offset (clock_offset_ns) is played by shifting
// the epoch the board is given, so board time b(t) matches the contract: b = t + offset
// when synchronized, b = offset + t (1 + ppm 1e-6) when free-running. During sync_loss the
// board gets no sync and holds over on the rate it learned (so it drifts by its residual
// rate error, not by clock_ppm as the contract formula assumes).
#include <cstdint>
#include <memory>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/sim/led_emitter.hpp"
#include "tetrapulse/sim/scenario.hpp"
#include "tetrapulse/sim_board/host_port.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::sim {

struct FirmwareEmitterOptions {
  int64_t lead_in_ns = 8'000'000'000;   // boards power up this long before frame 0
  int64_t can_sync_period_ns = 100'000'000;
  int64_t can_latency_ns = 50'000;      // each Sync arrives 0..this late (seeded)
  uint64_t seed = 1;
};

// What the board of target `index` is, and how it is synchronized; shared with the host's
// virtual rig (host/sim_rig.hpp), which configures and syncs the same boards through the
// host's Board and sync master code instead.
sim_board::SimBoardOptions firmware_board_options(const Scenario& scenario, size_t index,
                                                  const FirmwareEmitterOptions& options);
// The configuration the board of target `index` is given: protocol::target_config of the
// scenario's targets, with the board's own epoch and, for GPIO sync, edge k = frame k's
// exposure start (numbered from the coarse time of FollowUps, so missed edges do not shift
// the count).
protocol::Config firmware_board_config(const Scenario& scenario, size_t index, int64_t power_on_ns);
// The epoch the board is given, in its own time, so that its b(t) is the contract's (header).
int64_t firmware_board_epoch_ns(const Scenario& scenario, size_t index, int64_t power_on_ns);
// GPIO: rig time of the first strobe edge (a second after power-up, on the frame grid); the
// host's coarse-time FollowUps go over USB from half a second before it, once a second,
// arriving kCoarseTimeLatencyNs late.
int64_t firmware_first_sync_edge_ns(const Scenario& scenario, const FirmwareEmitterOptions& options);
constexpr int64_t kCoarseTimeLatencyNs = 300'000;
// CAN: how late each Sync reaches board `index`, 0..options.can_latency_ns, drawn in order
// for the Syncs it receives (seeded).
class CanSyncLatency {
 public:
  CanSyncLatency(const FirmwareEmitterOptions& options, size_t index);
  int64_t next();

 private:
  int64_t max_ns_;
  uint64_t state_;
};

class FirmwareBoardEmitter : public LedEmitter {
 public:
  FirmwareBoardEmitter(const Scenario& scenario, size_t index, const FirmwareEmitterOptions& options = {});
  ~FirmwareBoardEmitter() override;

  // False when the board refused the configuration (firmware_board_emitter then falls
  // back to the contract formula).
  bool configured() const { return configured_; }
  // Runs the board (and its sync) up to rig time t.
  void run_until(int64_t rig_ns) const;
  const sim_board::SimBoard& board() const { return *board_; }

 private:
  double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const override;
  void feed_sync_until(int64_t rig_ns) const;

  FirmwareEmitterOptions options_;
  BoardSync sync_;
  TimeIntervals sync_loss_;
  int64_t edge_period_ns_ = 0;
  mutable std::unique_ptr<sim_board::SimBoard> board_;
  mutable std::unique_ptr<sim_board::HostPort> host_;
  mutable int64_t next_sync_ns_ = 0;  // next GPIO edge, or next CAN Sync's transmit time
  mutable uint16_t sync_seq_ = 0;
  mutable int64_t next_coarse_ns_ = 0;  // GPIO: next coarse-time FollowUp (over USB)
  mutable uint16_t coarse_seq_ = 0;
  mutable CanSyncLatency latency_;
  bool configured_ = false;
};

// FirmwareBoardEmitter for target `index`, or the contract formula when the board cannot
// play the target's configuration.
std::unique_ptr<LedEmitter> firmware_board_emitter(const Scenario& scenario, size_t index,
                                                   const FirmwareEmitterOptions& options = {});

}  // namespace tetrapulse::sim
