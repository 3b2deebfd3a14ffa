#pragma once
// The Linux board's flash: a file with the same rules as on-chip flash (erased bytes read
// 0xFF, programming only clears bits, whole-sector erases), so the core's record store and
// update code keep their power-cut safety. Every program and erase reaches the disk
// (fdatasync) before it returns: a power cut or a killed daemon leaves the file as a torn
// flash write would leave a chip, which the record store recovers from.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/linux_board/board_error.hpp"

namespace tetrapulse::linux_board {

// Record store in two 4 KB sectors at 0x0 and 0x1000; slot 0 in four 64 KB sectors at
// 0x10000, slot 1 at 0x50000; both slots take images with load_address 0 (the board runs
// the same program from either). File size 0x90000 (576 KB).
fw::FlashLayout linux_flash_layout();
std::vector<fw::FlashRegion> linux_flash_sectors();

class FileFlash final : public fw::Flash {
 public:
  // Opens `path`, creating it erased (all 0xFF) at the size of `sectors` when missing
  // (created() then says so). kFlash naming the file when it cannot be created or opened, or
  // its size is not that of `sectors`.
  static BoardResult<std::unique_ptr<FileFlash>> open(const std::string& path, std::vector<fw::FlashRegion> sectors);
  ~FileFlash();
  FileFlash(const FileFlash&) = delete;
  FileFlash& operator=(const FileFlash&) = delete;

  const std::string& path() const { return path_; }
  // Whether open() made the file (a new board: the factory programs it).
  bool created() const { return created_; }
  // Writes without the flash rules (factory programming of an erased file).
  protocol::Status load(uint32_t address, protocol::ByteView data);
  // Test hook standing in for a power cut: after `bytes` more programmed bytes or erased
  // sectors, writes stop (the one in progress keeps only its prefix) and fail.
  void cut_power_after(uint64_t bytes) { budget_ = bytes; }

 private:
  FileFlash(std::string path, int fd, std::vector<fw::FlashRegion> sectors, bool created);
  protocol::Result<fw::FlashRegion> do_sector_at(uint32_t address) const override;
  protocol::Status do_erase_sector(uint32_t sector_address) override;
  protocol::Status do_program(uint32_t address, protocol::ByteView data) override;
  protocol::Status do_read(uint32_t address, uint8_t* out, size_t size) const override;

  bool in_range(uint32_t address, size_t size) const;
  bool write_at(uint32_t address, const uint8_t* data, size_t size);

  std::string path_;
  int fd_;
  std::vector<fw::FlashRegion> sectors_;
  uint32_t base_;
  uint32_t end_;
  bool created_;
  uint64_t budget_ = UINT64_MAX;
};

}  // namespace tetrapulse::linux_board
