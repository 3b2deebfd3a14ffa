#pragma once
// The reference board's pinout (STM32F405RG, LQFP64): the one table that drivers, and
// hardware/'s wiring notes, take their pins from. Alternate-function numbers are the
// STM32F405 datasheet's (AF1 TIM1/2, AF3 TIM8, AF7 USART1, AF9 CAN1, AF10 OTG_FS).
//
// Choices: the four LED channels are TIM8_CH1..4 on PC6..PC9 because TIM1's CH4 (PA11)
// and the USB pins (PA11/PA12) collide; USART1 is on PB6/PB7 so that PA9 stays free for
// USB VBUS; the sync input is TIM2_CH2 so that TIM2's CH1 can time LED updates.
#include <cstdint>

#include "tetrapulse/stm32f405/registers/gpio.hpp"

namespace tetrapulse::stm32f405 {

struct Pin {
  gpio::Port port;
  uint8_t number;     // 0..15
  uint8_t alternate;  // AF number, when the pin is used in alternate-function mode
};

enum class Signal : uint8_t {
  kLed0, kLed1, kLed2, kLed3,  // TIM8_CH1..4: PWM to the LED current drivers
  kSyncInput,                  // TIM2_CH2: camera strobe / trigger, input capture
  kUartTx, kUartRx,            // USART1
  kCanRx, kCanTx,              // CAN1, to the transceiver
  kUsbDm, kUsbDp,              // OTG_FS
};

struct PinAssignment {
  Signal signal;
  Pin pin;
  const char* name;  // the pin as printed in the datasheet
  const char* role;  // what the board connects to it
};

constexpr PinAssignment kPinout[] = {
    {Signal::kLed0, {gpio::Port::kC, 6, 3}, "PC6", "TIM8_CH1, marker 0 LED driver (PWM, active high)"},
    {Signal::kLed1, {gpio::Port::kC, 7, 3}, "PC7", "TIM8_CH2, marker 1 LED driver"},
    {Signal::kLed2, {gpio::Port::kC, 8, 3}, "PC8", "TIM8_CH3, marker 2 LED driver"},
    {Signal::kLed3, {gpio::Port::kC, 9, 3}, "PC9", "TIM8_CH4, marker 3 LED driver"},
    {Signal::kSyncInput, {gpio::Port::kA, 1, 1}, "PA1", "TIM2_CH2, sync input (3.3 V logic, pull-down)"},
    {Signal::kUartTx, {gpio::Port::kB, 6, 7}, "PB6", "USART1_TX, 115200 8N1"},
    {Signal::kUartRx, {gpio::Port::kB, 7, 7}, "PB7", "USART1_RX (pull-up)"},
    {Signal::kCanRx, {gpio::Port::kB, 8, 9}, "PB8", "CAN1_RX, from the transceiver's RXD"},
    {Signal::kCanTx, {gpio::Port::kB, 9, 9}, "PB9", "CAN1_TX, to the transceiver's TXD"},
    {Signal::kUsbDm, {gpio::Port::kA, 11, 10}, "PA11", "OTG_FS_DM"},
    {Signal::kUsbDp, {gpio::Port::kA, 12, 10}, "PA12", "OTG_FS_DP (bus powered, VBUS sensing off)"},
};

constexpr Pin pin_of(Signal s) {
  for (const PinAssignment& a : kPinout) {
    if (a.signal == s) return a.pin;
  }
  return Pin{gpio::Port::kA, 0, 0};  // unreachable: every Signal is in the table (checked below)
}

constexpr bool every_signal_assigned() {
  for (uint8_t s = 0; s <= static_cast<uint8_t>(Signal::kUsbDp); ++s) {
    bool found = false;
    for (const PinAssignment& a : kPinout) found = found || a.signal == static_cast<Signal>(s);
    if (!found) return false;
  }
  return true;
}
static_assert(every_signal_assigned(), "every signal needs a pin");

// The 8 MHz crystal sits on PH0/PH1 (OSC_IN/OSC_OUT); SWD on PA13/PA14.
constexpr uint32_t kHseHz = 8'000'000;

}  // namespace tetrapulse::stm32f405
