#pragma once
// A small power-loss-safe key -> value store in two flash sectors, shared by the
// application (configuration) and the bootloader (boot state).
//
// Each sector starts with a header {magic, generation, CRC}; the sector with the valid
// header of highest generation is active. Records are appended to the active sector:
//   [magic u16][key u8][0][length u16][0 u16][seq u32][crc32c u32][payload][0xFF pad to 8]
// the CRC-32C covering bytes 0..11 and the payload; the newest record of a key wins.
// When the active sector is full, or ends in a torn record (power cut mid-write), the
// newest record of every key is copied into the other sector, erased first, and that
// sector's header is written last: the commit point. So a power cut at any byte of any
// write or erase leaves either the old or the new value of every key, never garbage.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

class RecordStore {
 public:
  static constexpr size_t kMaxKeys = 8;           // keys 1..kMaxKeys
  static constexpr size_t kMaxPayload = 128;
  static constexpr size_t kHeaderSize = 16;       // sector header and record header
  static constexpr size_t kAlignment = 8;

  RecordStore(Flash& flash, const std::array<FlashRegion, 2>& sectors)
      : flash_(flash), sectors_(sectors) {}

  // Reads both sectors and indexes the newest record of each key. kFlashError when flash
  // cannot be read; a store with no valid sector is empty (not an error).
  protocol::Status open();

  // Copies the newest payload of `key` into `out` and returns its length; kInvalidState
  // when there is none, kBufferTooSmall when it does not fit.
  protocol::Result<size_t> read(uint8_t key, uint8_t* out, size_t capacity) const;
  bool contains(uint8_t key) const;

  // Stores `payload` under `key` (1..kMaxKeys, payload <= kMaxPayload bytes): kBadValue
  // for those, kFlashError when flash fails (then the old value stays).
  protocol::Status write(uint8_t key, protocol::ByteView payload);

  // Flash operations since open() (for tests).
  uint32_t compactions() const { return compactions_; }

 private:
  struct Entry {
    bool present = false;
    uint32_t address = 0;  // of the record header
    uint16_t length = 0;
    uint32_t seq = 0;
  };

  protocol::Status scan(size_t sector);
  protocol::Status append(size_t sector, uint32_t at, uint8_t key, protocol::ByteView payload, uint32_t seq);
  protocol::Status compact(uint8_t key, protocol::ByteView payload);
  bool read_header(size_t sector, uint32_t* generation) const;

  Flash& flash_;
  std::array<FlashRegion, 2> sectors_;
  bool have_active_ = false;
  size_t active_ = 0;
  uint32_t generation_ = 0;
  uint32_t write_at_ = 0;    // next free byte in the active sector
  bool torn_ = false;        // the active sector ends in a torn record: compact before writing
  uint32_t next_seq_ = 1;
  Entry entries_[kMaxKeys + 1];
  uint32_t compactions_ = 0;
};

// Keys of the records the application and the bootloader keep.
constexpr uint8_t kConfigRecordKey = 1;
constexpr uint8_t kBootStateRecordKey = 2;

}  // namespace tetrapulse::fw
