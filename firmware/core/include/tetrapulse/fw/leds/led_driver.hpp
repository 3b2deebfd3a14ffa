#pragma once
// Hardware seam: the four marker LEDs, each a PWM output whose duty changes exactly at
// a scheduled local tick (a timer compare event), never by polling.
//
// stm32f405: compare channels of the local counter's timer load the PWM duty;
// boards/sim: records {tick, marker, duty} into the LED log that tests and the
// virtual rig read.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

constexpr uint8_t kLedCount = 4;        // markers 0..3
constexpr uint16_t kDutyFull = 65535;   // duty is a fraction x/65535 of full emission

class LedDriver {
 public:
  // Marker `index` (0..3) goes to `duty` (0 off .. 65535 full) at local tick `at`.
  // Changes of one marker are scheduled in increasing `at`. kBusy when `index` already
  // holds queue_depth() changes not yet applied; kInvalidState when `at` is less than
  // lead_ticks() after now (too late to arm the compare); kBadValue for index > 3.
  protocol::Status schedule(uint8_t index, uint16_t duty, Tick at) { return do_schedule(index, duty, at); }
  // Changes of marker `index` scheduled and not yet applied.
  size_t pending(uint8_t index) const { return do_pending(index); }
  // Drops every change not yet applied, on all markers; outputs keep their duty.
  void cancel() { do_cancel(); }
  // Sets marker `index` to `duty` at once (start-up, shutdown, after cancel()).
  void set_now(uint8_t index, uint16_t duty) { do_set_now(index, duty); }

  // How far ahead of its tick a change must be scheduled.
  uint32_t lead_ticks() const { return do_lead_ticks(); }
  // How many changes per marker the driver holds (>= 1).
  size_t queue_depth() const { return do_queue_depth(); }
  // LED current at duty 65535, mA (Config.current_limit_ma is a fraction of it).
  uint16_t full_scale_ma() const { return do_full_scale_ma(); }

 protected:
  ~LedDriver() = default;

 private:
  virtual protocol::Status do_schedule(uint8_t index, uint16_t duty, Tick at) = 0;
  virtual size_t do_pending(uint8_t index) const = 0;
  virtual void do_cancel() = 0;
  virtual void do_set_now(uint8_t index, uint16_t duty) = 0;
  virtual uint32_t do_lead_ticks() const = 0;
  virtual size_t do_queue_depth() const = 0;
  virtual uint16_t do_full_scale_ma() const = 0;
};

}  // namespace tetrapulse::fw
