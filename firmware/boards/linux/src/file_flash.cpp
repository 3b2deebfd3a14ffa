#include "tetrapulse/linux_board/file_flash.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "tetrapulse/protocol/image_header.hpp"

namespace tetrapulse::linux_board {

using protocol::Error;

std::vector<fw::FlashRegion> linux_flash_sectors() {
  std::vector<fw::FlashRegion> sectors = {{0x0000, 0x1000}, {0x1000, 0x1000}};
  // 0x2000..0x10000: a gap of unused 8 KB sectors keeps slot bases 64 KB aligned.
  for (uint32_t a = 0x2000; a < 0x10000; a += 0x2000) sectors.push_back({a, 0x2000});
  for (uint32_t a = 0x10000; a < 0x90000; a += 0x10000) sectors.push_back({a, 0x10000});
  return sectors;
}

fw::FlashLayout linux_flash_layout() {
  fw::FlashLayout layout;
  layout.record_sectors = {fw::FlashRegion{0x0000, 0x1000}, fw::FlashRegion{0x1000, 0x1000}};
  layout.slots[0] = fw::SlotLayout{fw::FlashRegion{0x10000, 0x40000}, 0};
  layout.slots[1] = fw::SlotLayout{fw::FlashRegion{0x50000, 0x40000}, 0};
  layout.vector_alignment = protocol::kMinVectorAlignment;
  return layout;
}

BoardResult<std::unique_ptr<FileFlash>> FileFlash::open(const std::string& path, std::vector<fw::FlashRegion> sectors) {
  const uint32_t size = sectors.empty() ? 0 : sectors.back().end() - sectors.front().address;
  const auto failed = [&](std::string message) { return board_error(BoardErrorKind::kFlash, path, std::move(message)); };
  bool created = false;
  int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0 && errno == ENOENT) {
    // Created under a temporary name and renamed once erased, so a half-made file never
    // passes for flash.
    const std::string temporary = path + ".new";
    fd = ::open(temporary.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return failed(std::string("cannot create: ") + std::strerror(errno));
    const std::vector<uint8_t> erased(size, 0xFF);
    if (::pwrite(fd, erased.data(), erased.size(), 0) != static_cast<ssize_t>(erased.size()) || ::fsync(fd) != 0 ||
        ::rename(temporary.c_str(), path.c_str()) != 0) {
      const int e = errno;
      ::close(fd);
      return failed(std::string("cannot write an erased flash file: ") + std::strerror(e));
    }
    created = true;
  }
  if (fd < 0) return failed(std::string("cannot open: ") + std::strerror(errno));
  struct stat st{};
  if (::fstat(fd, &st) != 0 || st.st_size != static_cast<off_t>(size)) {
    ::close(fd);
    return failed("is " + std::to_string(st.st_size) + " bytes, not the board's " + std::to_string(size) +
                  " bytes of flash");
  }
  return std::unique_ptr<FileFlash>(new FileFlash(path, fd, std::move(sectors), created));
}

FileFlash::FileFlash(std::string path, int fd, std::vector<fw::FlashRegion> sectors, bool created)
    : path_(std::move(path)),
      fd_(fd),
      sectors_(std::move(sectors)),
      base_(sectors_.front().address),
      end_(sectors_.back().end()),
      created_(created) {}

FileFlash::~FileFlash() { ::close(fd_); }

bool FileFlash::in_range(uint32_t address, size_t size) const {
  return address >= base_ && size <= end_ - base_ && address - base_ <= end_ - base_ - size;
}

bool FileFlash::write_at(uint32_t address, const uint8_t* data, size_t size) {
  size_t allowed = size;
  if (budget_ < size) allowed = static_cast<size_t>(budget_);
  budget_ -= allowed;
  if (allowed > 0) {
    if (::pwrite(fd_, data, allowed, address - base_) != static_cast<ssize_t>(allowed)) return false;
    if (::fdatasync(fd_) != 0) return false;
  }
  return allowed == size;
}

protocol::Result<fw::FlashRegion> FileFlash::do_sector_at(uint32_t address) const {
  for (const fw::FlashRegion& s : sectors_) {
    if (address >= s.address && address < s.end()) return s;
  }
  return Error::kBadValue;
}

protocol::Status FileFlash::do_erase_sector(uint32_t sector_address) {
  const protocol::Result<fw::FlashRegion> sector = do_sector_at(sector_address);
  if (!sector || sector->address != sector_address) return Error::kBadValue;
  if (budget_ == 0) return Error::kFlashError;
  --budget_;  // an erase counts as one step: it either happened or did not
  const std::vector<uint8_t> erased(sector->size, 0xFF);
  if (::pwrite(fd_, erased.data(), erased.size(), sector_address - base_) != static_cast<ssize_t>(erased.size()) ||
      ::fdatasync(fd_) != 0) {
    return Error::kFlashError;
  }
  return {};
}

protocol::Status FileFlash::do_program(uint32_t address, protocol::ByteView data) {
  if (!in_range(address, data.size)) return Error::kBadValue;
  std::vector<uint8_t> old(data.size);
  if (::pread(fd_, old.data(), old.size(), address - base_) != static_cast<ssize_t>(old.size())) {
    return Error::kFlashError;
  }
  for (size_t i = 0; i < data.size; ++i) {
    if ((old[i] & data[i]) != data[i]) return Error::kFlashError;  // a 0 bit to 1: not erased
  }
  if (!write_at(address, data.data, data.size)) return Error::kFlashError;
  return {};
}

protocol::Status FileFlash::do_read(uint32_t address, uint8_t* out, size_t size) const {
  if (!in_range(address, size)) return Error::kBadValue;
  if (size == 0) return {};
  if (::pread(fd_, out, size, address - base_) != static_cast<ssize_t>(size)) return Error::kFlashError;
  return {};
}

protocol::Status FileFlash::load(uint32_t address, protocol::ByteView data) {
  if (!in_range(address, data.size)) return Error::kBadValue;
  if (!write_at(address, data.data, data.size)) return Error::kFlashError;
  return {};
}

}  // namespace tetrapulse::linux_board
