#pragma once
// USART1 (pinout.hpp) as a byte stream (fw::SerialPort): 8N1, interrupt-driven receive
// and transmit through two queues, so the main loop never waits for the line.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/app/spsc_queue.hpp"
#include "tetrapulse/fw/links/uart_link.hpp"

namespace tetrapulse::stm32f405 {

class Usart1 final : public fw::SerialPort {
 public:
  // Not constexpr on purpose: a constant-initialised object with a vtable lands in .data
  // and costs its whole size in flash as well (its copy there); this one is built at first
  // use in zeroed RAM (.bss) instead.
  Usart1();
  // 22 ms of bytes at 115200 baud; the main loop empties it every pass, well under 1 ms
  // apart (while flash is erased the core stalls and bytes are lost whatever the size).
  static constexpr size_t kRxQueue = 256;
  // One whole frame (SPEC §6.1: 325 bytes) and room to spare: a host waits for each answer
  // before it sends the next request, and the board sends nothing on its own over UART.
  static constexpr size_t kTxQueue = 512;

  // `apb2_hz` as configure_clocks() reported it.
  void start(uint32_t apb2_hz, uint32_t baud);

  bool read(uint8_t* byte) { return rx_.pop(byte); }
  // Waits (bounded) until every queued byte has left the shift register: before a reset.
  void drain();

  uint32_t overruns() const { return overruns_; }
  uint32_t line_errors() const { return line_errors_; }

  void on_interrupt();

 private:
  protocol::Status do_write(protocol::ByteView bytes) override;
  void fill_transmitter();

  fw::SpscQueue<uint8_t, kRxQueue> rx_;
  uint8_t tx_[kTxQueue] = {};  // written under an interrupt lock, so a plain ring
  size_t tx_head_ = 0;
  size_t tx_count_ = 0;
  volatile uint32_t overruns_ = 0;
  volatile uint32_t line_errors_ = 0;
};

Usart1& usart1();

}  // namespace tetrapulse::stm32f405
