#pragma once
// The target board's firmware, above the hardware seams: a board (stm32f405, sim)
// builds the seams, hands them over in FirmwareParts, calls start() once after reset,
// then feeds events and calls poll() from its main loop:
//
//   Firmware fw(parts);            // parts.clock, leds, flash, system, sync_input, can ...
//   fw.start();                    // record store, configuration, boot confirmation
//   for (;;) {
//     while (edges.pop(&t)) fw.on_sync_edge(t);   // captured sync edges
//     can_link.on_frame(frame, rx, fw);           // links deliver messages to fw
//     fw.poll();                                  // LEDs, identify, confirm, watchdog
//   }
//
// Every call comes from one context (the main loop, or interrupts of one priority).
#include <cstdint>

#include "tetrapulse/fw/app/board_state.hpp"
#include "tetrapulse/fw/app/command_handler.hpp"
#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"

namespace tetrapulse::fw {

class Firmware final : public MessageSink {
 public:
  explicit Firmware(const FirmwareParts& parts);

  // Opens the record store, loads and applies the stored configuration, reads the boot
  // state. Call once after reset.
  void start();
  // A sync edge captured at local tick `captured`.
  void on_sync_edge(Tick captured);
  // Main loop work: LED schedule, end of identify, boot confirmation, watchdog kick.
  void poll();

  // One message through the command handler (what on_message does, minus sending).
  CommandReply handle(protocol::ByteView message, Tick rx_tick, LinkKind link, uint8_t* out, size_t capacity);

  BoardState& board() { return board_; }
  const BoardState& board() const { return board_; }
  // True once this image has confirmed itself in the boot state (or had nothing to confirm).
  bool confirmed() const { return confirmed_; }

 private:
  void do_on_message(const ReceivedMessage& message) override;
  void confirm_if_healthy(Tick now);

  BoardState board_;
  CommandHandler handler_;
  Tick started_at_ = 0;
  bool confirmed_ = false;
};

}  // namespace tetrapulse::fw
