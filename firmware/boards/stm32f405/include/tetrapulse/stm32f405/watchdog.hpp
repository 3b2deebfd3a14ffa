#pragma once
// The independent watchdog: once started it cannot be stopped; the main loop feeds it.
#include <cstdint>

namespace tetrapulse::stm32f405 {

// Starts the IWDG with a timeout of about `timeout_ms` (LSI ~32 kHz, /64: 2 ms steps,
// at most 8 s). The LSI varies 17-47 kHz over parts and temperature, so the real
// timeout lies between 0.7x and 1.9x of this.
void start_watchdog(uint32_t timeout_ms);
void feed_watchdog();

}  // namespace tetrapulse::stm32f405
