#include "tetrapulse/stm32f405/gpio_setup.hpp"

#include "tetrapulse/stm32f405/registers/rcc.hpp"

namespace tetrapulse::stm32f405 {

void configure_alternate(Pin pin, uint32_t pull) {
  rcc::Registers& r = rcc::regs();
  r.AHB1ENR = r.AHB1ENR | bit(static_cast<unsigned>(pin.port));  // GPIOxEN is bit x
  (void)r.AHB1ENR;
  gpio::Registers& g = gpio::regs(pin.port);
  const unsigned two = 2u * pin.number;
  const unsigned four = 4u * (pin.number % 8);
  Reg& afr = g.AFR[pin.number / 8];
  afr = (afr & ~mask(4, four)) | field(pin.alternate, four);
  g.OTYPER = g.OTYPER & ~bit(pin.number);
  g.OSPEEDR = (g.OSPEEDR & ~mask(2, two)) | field(gpio::kSpeedVeryHigh, two);
  g.PUPDR = (g.PUPDR & ~mask(2, two)) | field(pull, two);
  g.MODER = (g.MODER & ~mask(2, two)) | field(gpio::kModeAlternate, two);
}

}  // namespace tetrapulse::stm32f405
