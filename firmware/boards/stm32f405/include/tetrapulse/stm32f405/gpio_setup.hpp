#pragma once
// Pin configuration from the pinout table.
#include <cstdint>

#include "tetrapulse/stm32f405/pinout.hpp"

namespace tetrapulse::stm32f405 {

// Clocks the pin's port and puts the pin in alternate-function mode (its AF from the
// table), push-pull, very high speed, with the given pull.
void configure_alternate(Pin pin, uint32_t pull = gpio::kPullNone);

}  // namespace tetrapulse::stm32f405
