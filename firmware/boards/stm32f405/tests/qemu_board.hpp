#pragma once
// The real application binary on an emulated STM32F405 (QEMU's netduinoplus2), driven
// over USART1 with the protocol's UART framing (SPEC.md §6). QEMU boots the real
// bootloader ELF; slot images (header and payload, the bytes a board gets) are loaded at
// their slots, 0x08020000 and 0x08040000; the bootloader checks them and starts one.
//
// The emulator's virtual time (the board's timers) either follows the host's clock, or
// counts instructions (-icount shift=auto). With the host's clock, a host busy with other
// tests stops the board while its timers run on, and the code player skips the LED edges
// it is then too late for (as a board that missed its deadlines should). Counting
// instructions, the board only runs slower; its time is steered towards the host's, but
// measured up to 4 times off over a second under load.
enum class VirtualClock { kHost, kInstructions };
#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::stm32f405::testing {

// The path in environment variable `variable` (set by CTest), or "" when it is not set.
std::string artefact(const char* variable);

// A request with sequence number `seq`.
protocol::Message request_message(uint8_t seq, protocol::Body body);

class QemuBoard {
 public:
  // An empty path leaves that slot erased.
  QemuBoard(const std::string& bootloader_elf, const std::string& slot0_image, const std::string& slot1_image = "",
            VirtualClock clock = VirtualClock::kInstructions);
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
