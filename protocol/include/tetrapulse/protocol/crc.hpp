#pragma once
// Checksums used on the wire and in flash.
#include <cstddef>
#include <cstdint>

namespace tetrapulse::protocol {

// CRC-32C (Castagnoli): reflected polynomial 0x82F63B78, init 0xFFFFFFFF,
// final xor 0xFFFFFFFF. crc32c("123456789") == 0xE3069283.
// Used for firmware images, flash records and multi-frame transfers over USB.
class Crc32c {
 public:
  void update(const uint8_t* data, size_t size);
  uint32_t value() const { return ~state_; }

 private:
  uint32_t state_ = 0xFFFFFFFFu;
};
uint32_t crc32c(const uint8_t* data, size_t size);

// CRC-16/CCITT-FALSE (also catalogued as CRC-16/IBM-3740): polynomial 0x1021,
// init 0xFFFF, not reflected, no final xor. crc16_ccitt("123456789") == 0x29B1.
// Used for CAN multi-frame transfers and UART frames (as Cyphal does).
class Crc16Ccitt {
 public:
  void update(const uint8_t* data, size_t size);
  uint16_t value() const { return state_; }

 private:
  uint16_t state_ = 0xFFFFu;
};
uint16_t crc16_ccitt(const uint8_t* data, size_t size);

}  // namespace tetrapulse::protocol
