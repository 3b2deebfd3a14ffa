#pragma once
// Reads the board's pin assignments from the two places that state them, so a test can
// hold them equal: the firmware's one pin table (kPinout and kHseHz in
// firmware/boards/stm32f405/include/tetrapulse/stm32f405/pinout.hpp) and the signal table
// of hardware/board/pinout.md (the table whose header starts with "signal (firmware)").
#include <string>
#include <vector>

#include <tl/expected.hpp>

namespace tetrapulse::board {

struct PinRow {
  std::string signal;    // the firmware's Signal name, e.g. "kLed0"
  char port = 0;         // GPIO port letter, 'A'..'I'
  int number = -1;       // pin within the port, 0..15
  int alternate = -1;    // alternate-function number AF0..AF15
  std::string function;  // the peripheral function on that pin, e.g. "TIM8_CH1"
};

struct PinTable {
  std::vector<PinRow> rows;  // in the order the source lists them
  long hse_hz = 0;           // the HSE crystal frequency, Hz
};

// Parses pinout.hpp: every Signal enumerator must appear in kPinout exactly once, the
// printed pin name ("PC6") must match the port and number, and kHseHz must be present.
// The function is the upper-case identifier the role string starts with ("TIM8_CH1, ...").
tl::expected<PinTable, std::string> read_firmware_pinout(const std::string& header_text);

// Parses pinout.md: the signal table (columns signal, pin, LQFP64, AF, function, ...)
// and the HSE frequency from the row that names kHseHz ("... 8 MHz ...").
tl::expected<PinTable, std::string> read_documented_pinout(const std::string& markdown_text);

// One line per disagreement ("kLed1: pin PC7 in firmware, PC10 documented"); empty when
// both state the same signals on the same pins, alternate functions and functions.
std::vector<std::string> pin_table_differences(const PinTable& firmware, const PinTable& documented);

}  // namespace tetrapulse::board
