#pragma once
// Hardware seam: on-chip flash with erase sectors. Erased bytes read 0xFF; programming
// only clears bits. Any operation may fail (kFlashError), and power may be cut in the
// middle of any of them: the record store and the update code are written so that a cut
// at any byte leaves a state they recover from.
//
// Addresses are byte addresses in the board's memory map (stm32f405: 0x08000000 on).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

// A span of flash, [address, address + size).
struct FlashRegion {
  uint32_t address = 0;
  uint32_t size = 0;

  uint32_t end() const { return address + size; }
  bool contains(uint32_t a, uint32_t n) const { return a >= address && n <= size && a - address <= size - n; }
};

class Flash {
 public:
  // The erase sector holding `address`; kBadValue outside the flash.
  protocol::Result<FlashRegion> sector_at(uint32_t address) const { return do_sector_at(address); }
  // Erases the whole sector that starts at `sector_address` to 0xFF (blocking).
  // kBadValue when it is not the first byte of a sector; kFlashError on failure.
  protocol::Status erase_sector(uint32_t sector_address) { return do_erase_sector(sector_address); }
  // Programs `data` at `address` (blocking). The core programs record-store records at
  // 8-byte aligned addresses in multiples of 8 bytes, and update images in chunks at any
  // offset and length (a board with a wider program unit buffers). kFlashError on failure
  // (including programming a byte that was not erased).
  protocol::Status program(uint32_t address, protocol::ByteView data) { return do_program(address, data); }
  // Copies `size` bytes at `address` into `out`; kBadValue outside the flash.
  protocol::Status read(uint32_t address, uint8_t* out, size_t size) const { return do_read(address, out, size); }

 protected:
  ~Flash() = default;

 private:
  virtual protocol::Result<FlashRegion> do_sector_at(uint32_t address) const = 0;
  virtual protocol::Status do_erase_sector(uint32_t sector_address) = 0;
  virtual protocol::Status do_program(uint32_t address, protocol::ByteView data) = 0;
  virtual protocol::Status do_read(uint32_t address, uint8_t* out, size_t size) const = 0;
};

}  // namespace tetrapulse::fw
