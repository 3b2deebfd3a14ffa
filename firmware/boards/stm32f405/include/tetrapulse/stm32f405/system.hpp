#pragma once
// Chip-level services: reset, reset cause, unique id, starting an image.
#include <array>
#include <cstdint>

namespace tetrapulse::stm32f405 {

// The 96-bit unique device id, in the chip's byte order (SPEC §2.6 Info.serial).
std::array<uint8_t, 12> unique_id();
// The id as 24 upper-case hex digits and a NUL (SPEC §5.1 serial string).
void unique_id_hex(char (&out)[25]);

struct ResetCause {
  bool watchdog = false;
  bool software = false;
  bool power_on = false;
  bool pin = false;
};
// Reads and clears the reset flags (RCC_CSR); call once at start.
ResetCause take_reset_cause();

[[noreturn]] void system_reset();

// Starts the image whose vector table is at `vector_table`: VTOR, MSP and the reset
// vector from the table. Interrupts must be quiet (every peripheral the caller enabled
// is reset first by the caller).
[[noreturn]] void start_image(uint32_t vector_table);

}  // namespace tetrapulse::stm32f405
