#pragma once
// The Linux board's four marker LEDs on GPIO output lines (libgpiod 1.6). A line has two
// levels: a duty above 0 lights it, 0 turns it off (no PWM from user space, so the board
// offers neither two-level codes nor a current limit). Scheduled changes are applied by
// the main loop when the local clock reaches their tick: it sleeps until next_due() and
// calls apply_due(); the lateness of each applied change is kept for the clock report.
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gpiod.hpp>

#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/leds/led_driver.hpp"
#include "tetrapulse/linux_board/board_error.hpp"

namespace tetrapulse::linux_board {

struct LedLateness {
  uint64_t applied = 0;
  int64_t last_ns = 0;  // how long after its tick the last change reached the line
  int64_t max_ns = 0;
};

class GpioLeds final : public fw::LedDriver {
 public:
  static constexpr uint32_t kLeadTicks = 300'000;  // 300 us: the main loop's wake-up budget
  static constexpr size_t kQueueDepth = 32;

  // `lines`: up to four "CHIP:LINE" texts, marker 0 first, each requested as an output;
  // markers without a line are played to nowhere. kGpio naming the line that cannot be had.
  static BoardResult<std::unique_ptr<GpioLeds>> open(const fw::LocalClock& clock, const std::vector<std::string>& lines);

  std::optional<fw::Tick> next_due() const;
  // Applies every change due at or before `now`.
  void apply_due(fw::Tick now);
  const LedLateness& lateness() const { return lateness_; }

 private:
  protocol::Status do_schedule(uint8_t index, uint16_t duty, fw::Tick at) override;
  size_t do_pending(uint8_t index) const override;
  void do_cancel() override;
  void do_set_now(uint8_t index, uint16_t duty) override;
  uint32_t do_lead_ticks() const override { return kLeadTicks; }
  size_t do_queue_depth() const override { return kQueueDepth; }
  uint16_t do_full_scale_ma() const override { return 20; }

  explicit GpioLeds(const fw::LocalClock& clock) : clock_(clock) {}
  void drive(uint8_t index, uint16_t duty);

  struct Change {
    fw::Tick at = 0;
    uint16_t duty = 0;
  };
  const fw::LocalClock& clock_;
  std::array<gpiod::line, fw::kLedCount> lines_;
  std::array<std::deque<Change>, fw::kLedCount> pending_;
  LedLateness lateness_;
};

}  // namespace tetrapulse::linux_board
