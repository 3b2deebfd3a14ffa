#include "tetrapulse/host/firmware_update.hpp"

#include <algorithm>
#include <thread>

#include <fmt/format.h>

namespace tetrapulse::host {
namespace {

class UpdateSession {
 public:
  UpdateSession(Board& board, const FirmwareImage& image, const UpdateOptions& options)
      : board_(board), image_(image), options_(options) {}

  HostResult<UpdateReport> run() {
    if (options_.chunk_size == 0 || options_.chunk_size > protocol::kMaxUpdateChunk) {
      return host_error(HostErrorKind::kBadInput, board_.name(),
                        fmt::format("chunk size {} is not 1..{}", options_.chunk_size, protocol::kMaxUpdateChunk));
    }
    const uint32_t size = static_cast<uint32_t>(image_.bytes.size());
    report("begin", 0, 1);
    const protocol::UpdateBegin begin{size, image_.header.fw_version, image_.crc32c};
    auto first = send(begin, board_.timeouts().flash);
    if (!first) return tl::unexpected(first.error());
    if (*first != 0) return aborted(malformed(fmt::format("update_begin: first expected offset {} (not 0)", *first)));

    for (uint32_t offset = 0; offset < size;) {
      if (options_.cancel != nullptr && options_.cancel->load()) {
        return aborted(HostError{HostErrorKind::kCancelled, board_.name(), "update cancelled"});
      }
      protocol::UpdateChunk chunk;
      chunk.offset = offset;
      chunk.length = static_cast<uint16_t>(std::min<size_t>(options_.chunk_size, size - offset));
      std::copy_n(image_.bytes.begin() + offset, chunk.length, chunk.data.begin());
      auto next = send(chunk, board_.timeouts().request);
      if (!next) return aborted(next.error());
      if (*next != offset + chunk.length) {
        return aborted(malformed(fmt::format("update_chunk at {}: the board expects {} next, not {}", offset, *next,
                                             offset + chunk.length)));
      }
      offset = *next;
      ++result_.chunks;
      report("write", offset, size);
    }

    report("verify", 0, 1);
    auto crc = verify();
    if (!crc) return aborted(crc.error());
    if (*crc != image_.crc32c) {
      return aborted(HostError{HostErrorKind::kVerifyFailed, board_.name(),
                               fmt::format("update_verify: board computed CRC 0x{:08X}, the image has 0x{:08X}", *crc,
                                           image_.crc32c)});
    }
    result_.crc32c = *crc;
    if (options_.reboot) {
      if (auto running = reboot_and_check(); !running) return tl::unexpected(running.error());
    }
    return result_;
  }

 private:
  void report(const char* stage, uint64_t done, uint64_t total) {
    if (options_.progress) options_.progress(FlashProgress{stage, done, total});
  }

  HostError malformed(std::string message) const {
    return HostError{HostErrorKind::kMalformed, board_.name(), std::move(message)};
  }

  // Sends a request answered by Ack, again (unchanged) when its answer is lost.
  HostResult<uint32_t> send(const protocol::Body& request, std::chrono::milliseconds timeout) {
    for (int attempt = 0;; ++attempt) {
      auto value = board_.command(request, timeout);
      if (value || value.error().kind != HostErrorKind::kTimeout || attempt >= options_.retries) return value;
      ++result_.resent;
    }
  }

  // UpdateVerify; a repeat after a lost Ack finds the update already verified.
  HostResult<uint32_t> verify() {
    for (int attempt = 0;; ++attempt) {
      auto crc = board_.command(protocol::UpdateVerify{}, board_.timeouts().flash);
      if (crc) return crc;
      if (attempt > 0 && crc.error().protocol_error == protocol::Error::kInvalidState) {
        auto status = board_.status();
        if (status && status->update_state == protocol::UpdateState::kVerified) return image_.crc32c;
      }
      if (crc.error().kind != HostErrorKind::kTimeout || attempt >= options_.retries) return crc;
      ++result_.resent;
    }
  }

  HostResult<void> reboot_and_check() {
    report("reboot", 0, 1);
    auto rebooted = board_.command(protocol::Reboot{protocol::RebootMode::kApplication}, board_.timeouts().request);
    if (!rebooted && rebooted.error().kind != HostErrorKind::kTimeout) return tl::unexpected(rebooted.error());
    // The board resets after its Ack (which may itself be lost as it goes): ask until it answers.
    const auto until = std::chrono::steady_clock::now() + options_.reboot_timeout;
    HostError last{HostErrorKind::kTimeout, board_.name(), "no answer"};
    for (;;) {
      auto info = board_.info();
      if (info) {
        result_.running_version = info->fw_version;
        if (info->fw_version != image_.header.fw_version) {
          return host_error(HostErrorKind::kVerifyFailed, board_.name(),
                            fmt::format("after the reboot the board runs version 0x{:08X}, not the image's 0x{:08X} "
                                        "(its bootloader refused the new slot)",
                                        info->fw_version, image_.header.fw_version));
        }
        report("reboot", 1, 1);
        return {};
      }
      last = info.error();
      if (std::chrono::steady_clock::now() >= until) {
        last.message = "did not come back after the reboot: " + last.message;
        return tl::unexpected(last);
      }
      if (last.kind != HostErrorKind::kTimeout) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  tl::unexpected<HostError> aborted(HostError error) {
    board_.command(protocol::UpdateAbort{}, board_.timeouts().request);  // best effort: the slot is never started
    return tl::unexpected(std::move(error));
  }

  Board& board_;
  const FirmwareImage& image_;
  const UpdateOptions& options_;
  UpdateReport result_;
};

}  // namespace

HostResult<UpdateReport> update_firmware(Board& board, const FirmwareImage& image, const UpdateOptions& options) {
  return UpdateSession(board, image, options).run();
}

}  // namespace tetrapulse::host
