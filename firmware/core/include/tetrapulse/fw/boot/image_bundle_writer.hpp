#pragma once
// Where a DFU download goes in a board's bootloader (SPEC.md §5.6, §7.2): a file of one or
// more firmware images back to back (a release's bundle holds one per slot, each linked
// for its slot). The writer parses each image header as the bytes stream in, writes the
// image whose load_address is the target slot's into that slot, and skips the others.
//
//   first block            erases the target slot (its pending mark is cleared first)
//   each header            decodes (else errFILE); for the target slot: fits the board
//                          (else errTARGET), fits the slot (else errADDRESS), only once
//                          (else errFILE)
//   manifestation          the file ended on an image boundary (else errNOTDONE), held an
//                          image for the slot (else errFILE), and that image passes
//                          check_slot_image: payload CRC-32C, fits, load address, vector
//                          alignment (else errVERIFY); then it is marked pending
//   flash failures         errERASE, errPROG, errWRITE (boot state)
// A single plain image linked for the target slot is a bundle of one.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/boot/image_check.hpp"
#include "tetrapulse/fw/storage/flash.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/fw/usb/dfu_target.hpp"
#include "tetrapulse/protocol/image_header.hpp"

namespace tetrapulse::fw {

class ImageBundleWriter final : public DfuDownloadTarget {
 public:
  // Poll-timeout estimates (ms) the host is told to wait: a slot erase (STM32F405 128 KB
  // sector at x8 parallelism: 2 s typical), and per 1024 bytes programmed (16 us/byte).
  static constexpr uint32_t kEraseMs = 2000;
  static constexpr uint32_t kProgramMsPerKiB = 17;
  static constexpr uint32_t kManifestMs = 100;

  // `target`: the slot downloads go to (update_target_slot()); `fallback`: the known-good
  // slot that stays confirmed (kNoSlot when there is none).
  ImageBundleWriter(Flash& flash, const FlashLayout& layout, RecordStore& store, const BoardModel& board,
                    uint8_t target, uint8_t fallback);

  uint8_t target_slot() const { return target_; }
  // The header of the image written, once one was found (for logs and tests).
  bool found_image() const { return found_; }
  const protocol::ImageHeader& image_header() const { return kept_; }

 private:
  protocol::DfuStatusCode do_download(uint32_t offset, protocol::ByteView block) override;
  uint32_t do_download_poll_ms(uint32_t offset, size_t size) const override;
  protocol::DfuStatusCode do_manifest(uint32_t size) override;
  uint32_t do_manifest_poll_ms() const override { return kManifestMs; }
  void do_abort() override;

  void restart();
  protocol::DfuStatusCode take_header();
  protocol::DfuStatusCode program(uint32_t image_offset, const uint8_t* data, size_t size);

  Flash& flash_;
  FlashLayout layout_;
  RecordStore& store_;
  BoardModel board_;
  uint8_t target_;
  uint8_t fallback_;

  uint32_t position_ = 0;      // bytes of the file consumed
  uint32_t image_start_ = 0;   // file offset of the image being parsed
  uint32_t image_size_ = 0;    // 0 while its header is incomplete
  bool keep_ = false;          // the current image is the target slot's
  uint8_t header_[protocol::kImageHeaderSize] = {};
  size_t header_fill_ = 0;
  bool found_ = false;
  protocol::ImageHeader kept_;
};

}  // namespace tetrapulse::fw
