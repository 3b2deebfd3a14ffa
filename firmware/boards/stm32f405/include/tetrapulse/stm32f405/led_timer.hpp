#pragma once
// The four marker LEDs on TIM8's PWM outputs (CH1..4, pinout.hpp), with every level
// change applied exactly at its scheduled local tick (fw::LedDriver).
//
// How a change lands on its tick, in hardware:
//   - TIM8's compare registers are preloaded (OCxPE): a new duty waits in the preload
//     register until TIM8's next update event (UEV).
//   - TIM2 (the local clock) matches CNT == CCR1 at the change's tick and pulses its
//     TRGO (master mode "compare pulse"). TIM8 runs in slave reset mode on ITR1 =
//     TIM2_TRGO: the pulse resets TIM8's counter and generates the UEV, which moves the
//     preloaded duties into the outputs. The delay from match to output is a fixed few
//     timer clocks (trigger resynchronisation), the same for every change.
//   - TIM8's own overflows would also generate UEVs and apply a preload early, so the
//     repetition counter (RCR = 255) spaces them 256 PWM periods apart (2.56 ms at the
//     100 kHz PWM), and a duty is only preloaded when no such UEV can come before its
//     tick: right after a UEV, for a change due before the next periodic one. TIM8's
//     update interrupt marks each UEV; a trigger UEV also restarts the spacing.
// Changes of several markers at one tick go out in one UEV.
//
// If the hardware trigger cannot have applied a change (armed too late, or an emulator
// without TIM8, or TIM2 compares as under QEMU), apply_overdue() from the main loop sets
// it by software and counts it late; on a working board it finds nothing to do.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/leds/led_driver.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"

namespace tetrapulse::stm32f405 {

class LedTimer final : public fw::LedDriver {
 public:
  // Not constexpr on purpose: a constant-initialised object with a vtable lands in .data
  // and costs its whole size in flash as well (its copy there); this one is built at first
  // use in zeroed RAM (.bss) instead.
  LedTimer();
  static constexpr size_t kQueueDepth = 8;
  static constexpr uint32_t kPwmHz = 100'000;

  // `apb2_timer_hz`: TIM8's clock from configure_clocks(); `clock`: the started TIM2.
  void start(uint32_t apb2_timer_hz, LocalTimer& clock);

  // Applies by software the changes whose tick passed without the hardware applying
  // them (see above). Main loop.
  void apply_overdue();
  uint32_t late_changes() const { return late_; }

  // Called from TIM8_UP_TIM13_IRQHandler.
  void on_update_event();

 private:
  struct Change {
    fw::Tick at = 0;
    uint16_t duty = 0;
  };
  struct Queue {
    Change items[kQueueDepth];
    size_t head = 0;
    size_t count = 0;
  };

  protocol::Status do_schedule(uint8_t index, uint16_t duty, fw::Tick at) override;
  size_t do_pending(uint8_t index) const override;
  void do_cancel() override;
  void do_set_now(uint8_t index, uint16_t duty) override;
  uint32_t do_lead_ticks() const override { return lead_ticks_; }
  size_t do_queue_depth() const override { return kQueueDepth; }
  uint16_t do_full_scale_ma() const override;

  uint32_t compare_value(uint16_t duty) const;
  void arm_next();          // interrupts masked
  void pop_applied(fw::Tick at);
  void write_now(uint8_t index, uint16_t duty);

  LocalTimer* clock_ = nullptr;
  uint32_t period_ = 0;            // TIM8 ARR + 1
  uint32_t uev_spacing_ticks_ = 0; // local ticks between periodic UEVs, minus a margin
  uint32_t lead_ticks_ = 0;
  Queue queues_[fw::kLedCount];
  uint16_t duty_[fw::kLedCount] = {};  // what the outputs show
  fw::Tick last_uev_ = 0;
  fw::Tick armed_ = 0;                 // tick of the change waiting in the preload; 0: none
  uint32_t late_ = 0;
};

LedTimer& led_timer();

}  // namespace tetrapulse::stm32f405
