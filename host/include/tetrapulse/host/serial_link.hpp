#pragma once
// A board on a serial line (a UART, USB CDC-ACM or a pseudo-terminal): termios raw mode,
// 8N1, no flow control, frames of protocol/SPEC.md §6 (COBS, CRC-16, 0x00 delimiter).
// Receive timestamps are when read() returned (a tty has no kernel timestamps), on
// CLOCK_MONOTONIC.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/link.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::host {

constexpr uint32_t kDefaultSerialBaud = 115200;  // SPEC.md §6

class SerialLink : public Link {
 public:
  // Opens `path` (exclusively) at `baud`, one of the standard rates 1200..4000000.
  // kNotFound when the path does not exist, kOpenFailed when it cannot be opened or is
  // not a tty, kBadInput for a rate termios does not have.
  static HostResult<std::unique_ptr<SerialLink>> open(const std::string& path, uint32_t baud = kDefaultSerialBaud);
  ~SerialLink() override;

 protected:
  HostResult<void> send_bytes(protocol::ByteView message) override;
  HostResult<std::optional<RawMessage>> receive_bytes(int64_t timeout_ns) override;

 private:
  SerialLink(std::string name, int fd) : Link(std::move(name)), fd_(fd) {}
  HostResult<void> write_all(const uint8_t* data, size_t size);

  int fd_;
  protocol::UartFrameDecoder decoder_;
  std::vector<uint8_t> unread_;  // bytes read but not yet fed to the decoder
  size_t unread_at_ = 0;
};

}  // namespace tetrapulse::host
