#pragma once
// The real application binary on an emulated STM32F405 (QEMU's netduinoplus2), driven
// over USART1 with the protocol's UART framing (SPEC.md §6). QEMU boots the real
// bootloader ELF; the slot 0 image (header and payload, the bytes a board gets) is
// loaded at 0x08020000; the bootloader checks it and starts it.
#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::stm32f405::testing {

class QemuBoard {
 public:
  QemuBoard(const std::string& bootloader_elf, const std::string& slot0_image);
  ~QemuBoard();
  QemuBoard(const QemuBoard&) = delete;
  QemuBoard& operator=(const QemuBoard&) = delete;

  bool running() const { return pid_ > 0; }

  // Sends one message in one UART frame.
  bool send(const protocol::Message& message);
  // Raw bytes onto the line (for malformed input).
  bool send_bytes(const std::vector<uint8_t>& bytes);
  // The next message the board sends, or nothing within `timeout_ms`.
  std::optional<protocol::Message> receive(int timeout_ms);
  // send, then the first response with the same seq.
  std::optional<protocol::Message> request(const protocol::Message& message, int timeout_ms = 2000);

  // Bytes that were not part of a valid frame (a healthy board sends none).
  size_t framing_errors() const { return framing_errors_; }

 private:
  pid_t pid_ = -1;
  int to_board_ = -1;
  int from_board_ = -1;
  protocol::UartFrameDecoder decoder_;
  std::vector<uint8_t> pending_;
  size_t pending_at_ = 0;
  size_t framing_errors_ = 0;
};

}  // namespace tetrapulse::stm32f405::testing
