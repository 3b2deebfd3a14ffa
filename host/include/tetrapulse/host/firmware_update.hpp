#pragma once
// Firmware update over the protocol (protocol/SPEC.md §7.3), on any link: UpdateBegin,
// UpdateChunk in order, UpdateVerify, then Reboot{application} and a check that the board
// runs the new version. A chunk whose Ack was lost is sent again as it was (the board
// acknowledges a repeat of its last chunk without writing it twice); any failure after
// UpdateBegin sends UpdateAbort, so the half-written slot is never started.
#include <chrono>
#include <cstdint>

#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/firmware_image.hpp"
#include "tetrapulse/host/flash_progress.hpp"

namespace tetrapulse::host {

struct UpdateOptions {
  size_t chunk_size = 256;  // image bytes per UpdateChunk, 1..256
  int retries = 4;          // extra sends of a request whose answer did not come
  bool reboot = true;       // Reboot{application} after verification, then check the version
  std::chrono::milliseconds reboot_timeout{15000};  // how long the board may take to answer again
  FlashProgressCallback progress;
  const CancelFlag* cancel = nullptr;
};

struct UpdateReport {
  uint32_t chunks = 0;
  uint32_t resent = 0;            // requests sent again after a lost answer
  uint32_t crc32c = 0;            // of the image, as the board confirmed it
  uint32_t running_version = 0;   // after the reboot (0 when not rebooted)
};

// Sends `image` as it is; choose_image() first picks the image the board takes.
HostResult<UpdateReport> update_firmware(Board& board, const FirmwareImage& image, const UpdateOptions& options);

}  // namespace tetrapulse::host
