#include "tetrapulse/stm32f405/usart1.hpp"

#include "tetrapulse/stm32f405/gpio_setup.hpp"
#include "tetrapulse/stm32f405/interrupt_handlers.hpp"
#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"
#include "tetrapulse/stm32f405/registers/usart.hpp"

namespace tetrapulse::stm32f405 {
namespace {
constexpr uint8_t kIrqPriority = 3;
}

Usart1& usart1() {
  static Usart1 port;
  return port;
}

void Usart1::start(uint32_t apb2_hz, uint32_t baud) {
  rcc::Registers& r = rcc::regs();
  r.APB2ENR = r.APB2ENR | rcc::kApb2Usart1;
  (void)r.APB2ENR;
  configure_alternate(pin_of(Signal::kUartTx));
  configure_alternate(pin_of(Signal::kUartRx), gpio::kPullUp);
  usart::Registers& u = usart::usart1();
  u.CR1 = 0;
  // Oversampling by 16: BRR = f_PCLK / baud, rounded (mantissa and 4-bit fraction together).
  u.BRR = (apb2_hz + baud / 2) / baud;
  u.CR2 = 0;
  u.CR3 = 0;
  u.CR1 = usart::kCr1Ue | usart::kCr1Te | usart::kCr1Re | usart::kCr1Rxneie;
  nvic::enable(nvic::kUsart1, kIrqPriority);
}

bool Usart1::write(const uint8_t* data, size_t size) {
  if (tx_.space() < size) return false;
  for (size_t i = 0; i < size; ++i) tx_.push(data[i]);
  InterruptLock lock;
  fill_transmitter();
  return true;
}

void Usart1::fill_transmitter() {
  // Fill the data register while it is free; TXEIE stays set only while bytes wait.
  // Called from write() as well as from the interrupt, because QEMU 7.2's USART model
  // raises no TXE interrupt at all (its transmitter is always free).
  usart::Registers& u = usart::usart1();
  uint8_t b;
  while ((u.SR & usart::kSrTxe) != 0) {
    if (!tx_.pop(&b)) {
      u.CR1 = u.CR1 & ~usart::kCr1Txeie;
      return;
    }
    u.DR = b;
  }
  u.CR1 = u.CR1 | usart::kCr1Txeie;
}

void Usart1::on_interrupt() {
  usart::Registers& u = usart::usart1();
  const uint32_t sr = u.SR;
  if ((sr & (usart::kSrRxne | usart::kSrOre)) != 0) {
    const uint8_t b = static_cast<uint8_t>(u.DR);  // reading DR clears RXNE and ORE
    if ((sr & usart::kSrOre) != 0) overruns_ = overruns_ + 1;
    if ((sr & (usart::kSrFe | usart::kSrNf)) != 0) line_errors_ = line_errors_ + 1;
    if (!rx_.push(b)) overruns_ = overruns_ + 1;
  }
  if ((u.CR1 & usart::kCr1Txeie) != 0) fill_transmitter();
}

}  // namespace tetrapulse::stm32f405

extern "C" void USART1_IRQHandler() { tetrapulse::stm32f405::usart1().on_interrupt(); }
