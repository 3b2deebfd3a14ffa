#pragma once
// Plays the four markers' codes: each change of level is scheduled on the LED driver
// at the local tick where the disciplined clock says its bit edge falls, a bounded time
// ahead (scheduled compares, not polling). Only edges where the level changes are
// scheduled. An Identify pattern overrides the codes while it lasts.
//
// service() is called from the main loop (and may be called on every LED compare): it
// tops up each marker's driver queue with the changes due within kHorizon. A change whose
// tick is already too close (the board was busy) is skipped, and the marker is set to the
// level of the current bit instead, so a late service never leaves a wrong level behind.
#include <array>
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/leds/led_driver.hpp"
#include "tetrapulse/fw/leds/led_log.hpp"
#include "tetrapulse/fw/leds/led_program.hpp"
#include "tetrapulse/fw/sync/clock_servo.hpp"

namespace tetrapulse::fw {

class CodePlayer {
 public:
  // Changes are scheduled at most this far ahead (rig ns).
  static constexpr int64_t kHorizonNs = 20'000'000;

  CodePlayer(LedDriver& leds, LedLog& log) : leds_(leds), log_(log) {}

  // The program to play from now on (a config change).
  void play(const LedProgram& program);
  // Plays `program` instead until local tick `until` (0: until stop_identify()).
  void identify(const LedProgram& program, Tick until);
  void stop_identify();
  bool identifying() const { return identifying_; }

  // Schedules what is due; reschedules everything when the clock stepped.
  void service(Tick now, const ClockMapping& clock, uint32_t clock_generation);

  uint32_t late_changes() const { return late_; }

 private:
  struct Cursor {
    int64_t bit = 0;        // bit number of the next change to schedule
    bool done = false;      // the marker never changes again (constant level)
    uint16_t duty = 0;      // the duty last scheduled
  };

  const LedProgram& active() const { return identifying_ ? identify_program_ : program_; }
  void restart(Tick now, const ClockMapping& clock);
  void advance(size_t m, Cursor& c) const;

  LedDriver& leds_;
  LedLog& log_;
  LedProgram program_;
  LedProgram identify_program_;
  bool identifying_ = false;
  Tick identify_until_ = 0;
  bool dirty_ = true;
  bool started_ = false;
  uint32_t generation_ = 0;
  std::array<Cursor, kLedCount> cursors_{};
  uint32_t late_ = 0;
};

}  // namespace tetrapulse::fw
