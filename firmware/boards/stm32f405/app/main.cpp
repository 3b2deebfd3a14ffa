// Probe: prints TIM2's count whenever a byte arrives.
#include "tetrapulse/stm32f405/clock_tree.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"
#include "tetrapulse/stm32f405/usart1.hpp"
using namespace tetrapulse::stm32f405;
static void put(uint64_t v) {
  uint8_t buf[24]; int n = 0; buf[23] = '\n';
  do { buf[22 - n++] = static_cast<uint8_t>('0' + v % 10); v /= 10; } while (v);
  usart1().write(buf + 23 - n, n + 1);
}
int main() {
  const Clocks c = configure_clocks();
  local_timer().start(c.apb1_timer_hz);
  usart1().start(c.apb2_hz, 115200);
  put(static_cast<uint64_t>(c.source));
  for (uint32_t i = 0;; ++i) {
    if (i % 200000000 == 0) put(local_timer().now());
    uint8_t b;
    if (usart1().read(&b)) put(local_timer().now());
  }
}
