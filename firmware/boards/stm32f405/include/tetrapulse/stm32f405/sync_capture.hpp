#pragma once
// fw::SyncInput on TIM2_CH2 (local_timer.hpp): edges captured in hardware, their ticks
// queued by the timer interrupt for the main loop.
#include "tetrapulse/fw/app/spsc_queue.hpp"
#include "tetrapulse/fw/sync/sync_input.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"

namespace tetrapulse::stm32f405 {

class SyncCapture final : public fw::SyncInput {
 public:
  explicit SyncCapture(LocalTimer& timer) : timer_(timer) {}
  // Main loop: the next captured edge.
  bool next_edge(fw::Tick* tick) { return edges_.pop(tick); }

 private:
  void do_configure(bool enabled, protocol::GpioEdge edge) override;
  static void on_capture(void* context, uint64_t tick);

  LocalTimer& timer_;
  fw::SpscQueue<fw::Tick, 16> edges_;
};

}  // namespace tetrapulse::stm32f405
