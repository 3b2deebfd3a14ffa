#include "tetrapulse/sim_board/sim_flash.hpp"

namespace tetrapulse::sim_board {

using protocol::Error;

SimFlash::SimFlash(std::vector<fw::FlashRegion> sectors, uint32_t erase_steps_per_sector)
    : sectors_(std::move(sectors)), erase_steps_(erase_steps_per_sector == 0 ? 1 : erase_steps_per_sector) {
  base_ = sectors_.empty() ? 0 : sectors_.front().address;
  const uint32_t end = sectors_.empty() ? 0 : sectors_.back().end();
  bytes_.assign(end - base_, 0xFF);
}

void SimFlash::cut_power_after(uint64_t steps) { cut_at_ = steps_ + steps; }

void SimFlash::restore_power() {
  powered_ = true;
  cut_at_.reset();
}

uint8_t SimFlash::noise() {
  // SplitMix64: the torn bytes differ from cut to cut but every run is the same.
  noise_state_ += 0x9E3779B97F4A7C15ull;
  uint64_t z = noise_state_;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return static_cast<uint8_t>(z ^ (z >> 31));
}

bool SimFlash::step() {
  if (!powered_) return false;
  if (cut_at_ && steps_ >= *cut_at_) {
    powered_ = false;
    return false;
  }
  ++steps_;
  return true;
}

bool SimFlash::in_range(uint32_t address, size_t size) const {
  return address >= base_ && size <= bytes_.size() && address - base_ <= bytes_.size() - size;
}

void SimFlash::load(uint32_t address, const std::vector<uint8_t>& data) {
  if (!in_range(address, data.size())) return;
  for (size_t i = 0; i < data.size(); ++i) bytes_[address - base_ + i] = data[i];
}

protocol::Result<fw::FlashRegion> SimFlash::do_sector_at(uint32_t address) const {
  for (const fw::FlashRegion& s : sectors_) {
    if (address >= s.address && address < s.end()) return s;
  }
  return Error::kBadValue;
}

protocol::Status SimFlash::do_erase_sector(uint32_t sector_address) {
  const protocol::Result<fw::FlashRegion> sector = do_sector_at(sector_address);
  if (!sector || sector->address != sector_address) return Error::kBadValue;
  if (failures_ > 0) {
    --failures_;
    return Error::kFlashError;
  }
  const uint32_t block = sector->size / erase_steps_;
  for (uint32_t k = 0; k < erase_steps_; ++k) {
    const uint32_t from = sector->address - base_ + k * block;
    const uint32_t to = k + 1 == erase_steps_ ? sector->end() - base_ : from + block;
    if (!step()) {
      if (!powered_ && cut_at_) {
        // The step the power died in: its bytes are neither old nor erased.
        for (uint32_t i = from; i < to; ++i) bytes_[i] = noise();
        cut_at_.reset();
      }
      return Error::kFlashError;
    }
    for (uint32_t i = from; i < to; ++i) bytes_[i] = 0xFF;
  }
  return {};
}

protocol::Status SimFlash::do_program(uint32_t address, protocol::ByteView data) {
  if (!in_range(address, data.size)) return Error::kBadValue;
  if (failures_ > 0) {
    --failures_;
    return Error::kFlashError;
  }
  for (size_t i = 0; i < data.size; ++i) {
    uint8_t& cell = bytes_[address - base_ + i];
    if (!step()) {
      if (!powered_ && cut_at_) {
        cell = static_cast<uint8_t>(cell & (data[i] | noise()));  // some of the bits cleared
        cut_at_.reset();
      }
      return Error::kFlashError;
    }
    if ((cell & data[i]) != data[i]) return Error::kFlashError;  // programming a 0 bit to 1: not erased
    cell = data[i];
  }
  return {};
}

protocol::Status SimFlash::do_read(uint32_t address, uint8_t* out, size_t size) const {
  if (!in_range(address, size)) return Error::kBadValue;
  for (size_t i = 0; i < size; ++i) out[i] = bytes_[address - base_ + i];
  return {};
}

}  // namespace tetrapulse::sim_board
