#pragma once
// Simulated on-chip flash with power-cut injection. A write *step* is one programmed byte
// or one erase step (a quarter of a sector by default); cut_power_after(k) lets k more
// steps complete, tears the next one (a programmed byte keeps a random subset of the bits
// it was clearing; an erase step leaves its bytes random) and ignores everything after it
// (kFlashError), until restore_power().
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "tetrapulse/fw/storage/flash.hpp"

namespace tetrapulse::sim_board {

class SimFlash final : public fw::Flash {
 public:
  // `sectors` contiguous and in address order.
  explicit SimFlash(std::vector<fw::FlashRegion> sectors, uint32_t erase_steps_per_sector = 4);

  void cut_power_after(uint64_t steps);
  void restore_power();
  bool powered() const { return powered_; }
  // Write steps completed since construction (to enumerate cut points).
  uint64_t steps() const { return steps_; }

  // The next `count` program/erase calls fail with kFlashError (nothing written).
  void fail_next(uint32_t count) { failures_ = count; }

  const std::vector<fw::FlashRegion>& sectors() const { return sectors_; }
  // Raw contents (tests compare images of flash before and after).
  const std::vector<uint8_t>& contents() const { return bytes_; }
  // Writes without the rules (factory programming).
  void load(uint32_t address, const std::vector<uint8_t>& data);

 private:
  protocol::Result<fw::FlashRegion> do_sector_at(uint32_t address) const override;
  protocol::Status do_erase_sector(uint32_t sector_address) override;
  protocol::Status do_program(uint32_t address, protocol::ByteView data) override;
  protocol::Status do_read(uint32_t address, uint8_t* out, size_t size) const override;

  // One more write step; false when the power is (now) gone.
  bool step();
  uint8_t noise();
  bool in_range(uint32_t address, size_t size) const;

  std::vector<fw::FlashRegion> sectors_;
  uint32_t erase_steps_;
  uint32_t base_;
  std::vector<uint8_t> bytes_;
  bool powered_ = true;
  std::optional<uint64_t> cut_at_;
  uint64_t steps_ = 0;
  uint32_t failures_ = 0;
  uint64_t noise_state_ = 0x9E3779B97F4A7C15ull;
};

}  // namespace tetrapulse::sim_board
