#pragma once
// USART1 (pinout.hpp) as a byte stream: 8N1, interrupt-driven receive and transmit
// through two queues, so the main loop never waits for the line.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/stm32f405/byte_ring.hpp"

namespace tetrapulse::stm32f405 {

class Usart1 {
 public:
  static constexpr size_t kRxQueue = 512;
  static constexpr size_t kTxQueue = 1024;  // three whole frames (SPEC §6.1: 325 bytes)

  // `apb2_hz` as configure_clocks() reported it.
  void start(uint32_t apb2_hz, uint32_t baud);

  bool read(uint8_t* byte) { return rx_.pop(byte); }
  // Queues all of `data` or nothing; false when the queue has no room for it.
  bool write(const uint8_t* data, size_t size);
  size_t write_space() const { return tx_.space(); }

  uint32_t overruns() const { return overruns_; }
  uint32_t line_errors() const { return line_errors_; }

  void on_interrupt();

 private:
  void fill_transmitter();

  ByteRing<kRxQueue> rx_;
  ByteRing<kTxQueue> tx_;
  volatile uint32_t overruns_ = 0;
  volatile uint32_t line_errors_ = 0;
};

Usart1& usart1();

}  // namespace tetrapulse::stm32f405
