#pragma once
// The STM32F405's 1 MB flash through its flash interface (RM0090 §3): sector erase and
// byte programming (x8 parallelism works at any supply voltage; images arrive in chunks
// at any offset), every operation checked by reading back. Reads are plain memory reads.
//
// The CPU stalls on flash fetches while an erase runs (a 128 KB sector takes 1-2 s), so
// the watchdog timeout must exceed that (main.cpp starts it with 4 s).
#include "tetrapulse/fw/storage/flash.hpp"

namespace tetrapulse::stm32f405 {

class InternalFlash final : public fw::Flash {
 private:
  protocol::Result<fw::FlashRegion> do_sector_at(uint32_t address) const override;
  protocol::Status do_erase_sector(uint32_t sector_address) override;
  protocol::Status do_program(uint32_t address, protocol::ByteView data) override;
  protocol::Status do_read(uint32_t address, uint8_t* out, size_t size) const override;
};

}  // namespace tetrapulse::stm32f405
