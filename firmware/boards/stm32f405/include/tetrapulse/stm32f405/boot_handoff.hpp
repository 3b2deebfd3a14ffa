#pragma once
// What the bootloader and the application tell each other across a reset or a jump: one
// small block at the top of SRAM1 that neither startup code clears (the linker scripts
// keep it out of .data/.bss). Reset leaves SRAM contents intact; power-on leaves garbage,
// which the magic word and the check word reject.
#include <cstdint>

#include "tetrapulse/stm32f405/memory_map.hpp"

namespace tetrapulse::stm32f405 {

struct BootHandoff {
  uint32_t magic;               // kHandoffMagic when the fields below are valid
  uint32_t request;             // application -> bootloader: BootRequest
  uint32_t bootloader_version;  // bootloader -> application: pack_version()
  uint32_t booted_slot;         // bootloader -> application: slot it started (0..1)
  uint32_t watchdog_resets;     // application's count since power-on; the bootloader keeps it
  uint32_t check;               // ~(magic ^ request ^ bootloader_version ^ booted_slot ^ watchdog_resets)
};

enum class BootRequest : uint32_t {
  kNone = 0,
  kStayInBootloader = 0xB0071D1E,  // DFU_DETACH or Reboot{bootloader}
};

constexpr uint32_t kHandoffMagic = 0x54504842;  // "BHPT"
constexpr uint32_t kHandoffAddress = kSramBase + kSramSize - 32;

inline BootHandoff& boot_handoff() { return *reinterpret_cast<BootHandoff*>(kHandoffAddress); }

inline uint32_t handoff_check(const BootHandoff& h) {
  return ~(h.magic ^ h.request ^ h.bootloader_version ^ h.booted_slot ^ h.watchdog_resets);
}
inline bool handoff_valid(const BootHandoff& h) {
  return h.magic == kHandoffMagic && h.check == handoff_check(h);
}
inline void seal_handoff(BootHandoff& h) {
  h.magic = kHandoffMagic;
  h.check = handoff_check(h);
}

}  // namespace tetrapulse::stm32f405
