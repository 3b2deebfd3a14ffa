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

protocol::Status Usart1::do_write(protocol::ByteView bytes) {
  InterruptLock lock;
  if (kTxQueue - tx_count_ < bytes.size) return protocol::Error::kBusy;
  for (size_t i = 0; i < bytes.size; ++i) tx_[(tx_head_ + tx_count_ + i) % kTxQueue] = bytes[i];
  tx_count_ += bytes.size;
  fill_transmitter();
  return {};
}

void Usart1::drain() {
  // 1024 bytes at 115200 baud take 89 ms; the bound is well above that at 168 MHz.
  usart::Registers& u = usart::usart1();
  for (uint32_t i = 0; i < 20'000'000; ++i) {
    bool idle;
    {
      InterruptLock lock;
      idle = tx_count_ == 0 && (u.SR & usart::kSrTc) != 0;
    }
    if (idle) return;
  }
}

void Usart1::fill_transmitter() {
  // Fill the data register while it is free; TXEIE stays set only while bytes wait.
  // Called from write() as well as from the interrupt, because QEMU 7.2's USART model
  // raises no TXE interrupt at all (its transmitter is always free).
  usart::Registers& u = usart::usart1();
  while ((u.SR & usart::kSrTxe) != 0) {
    if (tx_count_ == 0) {
      u.CR1 = u.CR1 & ~usart::kCr1Txeie;
      return;
    }
    u.DR = tx_[tx_head_];
    tx_head_ = (tx_head_ + 1) % kTxQueue;
    --tx_count_;
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
