#pragma once
// The simulated board's LED outputs: each scheduled change is applied exactly when the
// counter reaches its tick, and every applied change is logged with its local tick and
// the true rig time at which it happened (the board's VirtualClock). The virtual rig and
// the tests read that log.
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/leds/led_driver.hpp"

namespace tetrapulse::sim_board {

struct AppliedLedChange {
  uint8_t marker = 0;
  uint16_t duty = 0;
  fw::Tick tick = 0;       // local tick it was applied at
  long double rig_ns = 0;  // true rig time it was applied at
};

class SimLedDriver final : public fw::LedDriver {
 public:
  SimLedDriver(const fw::LocalClock& clock, uint32_t lead_ticks, size_t queue_depth, uint16_t full_scale_ma);

  // The earliest pending change over all markers: (marker, tick).
  std::optional<std::pair<uint8_t, fw::Tick>> next_due() const;
  // Applies the oldest pending change of `marker`, which happens at rig time `rig_ns`.
  void apply_next(uint8_t marker, long double rig_ns);
  // Sets every marker to `duty` at once (power-up, reset), at rig time `rig_ns`.
  void reset(long double rig_ns, fw::Tick tick);
  // Rig time of the board now (for set_now), set by the board before each call into firmware.
  void set_rig_now(long double rig_ns) { rig_now_ = rig_ns; }

  uint16_t duty(uint8_t marker) const { return duty_[marker]; }
  const std::vector<AppliedLedChange>& log() const { return log_; }
  // Changes of one marker, in time order.
  const std::vector<AppliedLedChange>& log(uint8_t marker) const { return per_marker_[marker]; }
  // Drops the changes before rig time t except each marker's last one (its level at t), so
  // a long run's log stays bounded; log() and mean_duty() then start there.
  void forget_before(long double rig_ns);
  // Mean duty (0..1) of `marker` over true rig times [t0, t1).
  double mean_duty(uint8_t marker, long double t0, long double t1) const;

 private:
  protocol::Status do_schedule(uint8_t index, uint16_t duty, fw::Tick at) override;
  size_t do_pending(uint8_t index) const override;
  void do_cancel() override;
  void do_set_now(uint8_t index, uint16_t duty) override;
  uint32_t do_lead_ticks() const override { return lead_ticks_; }
  size_t do_queue_depth() const override { return depth_; }
  uint16_t do_full_scale_ma() const override { return full_scale_ma_; }

  void record(uint8_t marker, uint16_t duty, fw::Tick tick, long double rig_ns);

  struct Pending {
    fw::Tick tick = 0;
    uint16_t duty = 0;
  };
  const fw::LocalClock& clock_;
  uint32_t lead_ticks_;
  size_t depth_;
  uint16_t full_scale_ma_;
  long double rig_now_ = 0;
  std::array<std::deque<Pending>, fw::kLedCount> pending_;
  std::array<uint16_t, fw::kLedCount> duty_{};
  std::vector<AppliedLedChange> log_;
  std::array<std::vector<AppliedLedChange>, fw::kLedCount> per_marker_;
};

}  // namespace tetrapulse::sim_board
