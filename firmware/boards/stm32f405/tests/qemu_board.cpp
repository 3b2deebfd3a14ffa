#include "qemu_board.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

namespace tetrapulse::stm32f405::testing {

namespace tp = protocol;

QemuBoard::QemuBoard(const std::string& bootloader_elf, const std::string& slot0_image) {
  int in[2];
  int out[2];
  if (pipe(in) != 0) return;
  if (pipe(out) != 0) {
    close(in[0]);
    close(in[1]);
    return;
  }
  const std::string loader = "loader,file=" + slot0_image + ",addr=0x08020000";
  pid_ = fork();
  if (pid_ == 0) {
    dup2(in[0], STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    close(in[1]);
    close(out[0]);
    execlp("qemu-system-arm", "qemu-system-arm", "-M", "netduinoplus2", "-display", "none", "-monitor", "none",
           "-serial", "stdio", "-kernel", bootloader_elf.c_str(), "-device", loader.c_str(),
           static_cast<char*>(nullptr));
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  to_board_ = in[1];
  from_board_ = out[0];
  if (pid_ < 0) {
    close(to_board_);
    close(from_board_);
  }
  signal(SIGPIPE, SIG_IGN);
}

QemuBoard::~QemuBoard() {
  if (to_board_ >= 0) close(to_board_);
  if (from_board_ >= 0) close(from_board_);
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
}

bool QemuBoard::send_bytes(const std::vector<uint8_t>& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(to_board_, bytes.data() + done, bytes.size() - done);
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

bool QemuBoard::send(const tp::Message& message) {
  uint8_t encoded[tp::kMaxMessageSize];
  tp::ByteWriter w(encoded, sizeof(encoded));
  if (!tp::encode(message, w)) return false;
  std::vector<uint8_t> frame(tp::kUartMaxFrameSize);
  const tp::Result<size_t> n = tp::encode_uart_frame(w.view(), frame.data(), frame.size());
  if (!n) return false;
  frame.resize(*n);
  return send_bytes(frame);
}

std::optional<tp::Message> QemuBoard::receive(int timeout_ms) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    while (pending_at_ < pending_.size()) {
      const tp::ReceiveEvent e = decoder_.push(pending_[pending_at_++]);
      if (e.kind == tp::ReceiveKind::kError) ++framing_errors_;
      if (e.kind != tp::ReceiveKind::kMessage) continue;
      const tp::Result<tp::Message> m = tp::decode(e.message);
      if (m) return *m;
      ++framing_errors_;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return std::nullopt;
    pollfd p{from_board_, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left)) <= 0) return std::nullopt;
    uint8_t buffer[512];
    const ssize_t n = read(from_board_, buffer, sizeof(buffer));
    if (n <= 0) return std::nullopt;
    pending_.assign(buffer, buffer + n);
    pending_at_ = 0;
  }
}

std::optional<tp::Message> QemuBoard::request(const tp::Message& message, int timeout_ms) {
  if (!send(message)) return std::nullopt;
  for (;;) {
    std::optional<tp::Message> m = receive(timeout_ms);
    if (!m || m->seq == message.seq) return m;
  }
}

}  // namespace tetrapulse::stm32f405::testing
