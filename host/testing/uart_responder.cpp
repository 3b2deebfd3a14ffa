#include "uart_responder.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>

#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::host::testing {

UartResponder::UartResponder(int fd, ResponderIdentity identity)
    : fd_(fd), responder_(identity), thread_([this] { run(); }) {}

UartResponder::~UartResponder() {
  stop_ = true;
  thread_.join();
}

void UartResponder::run() {
  protocol::UartFrameDecoder decoder;
  while (!stop_) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 20) <= 0) continue;
    uint8_t buffer[256];
    const ssize_t n = read(fd_, buffer, sizeof(buffer));
    if (n <= 0) continue;
    protocol::ByteView rest{buffer, static_cast<size_t>(n)};
    while (rest.size > 0) {
      size_t used = 0;
      const protocol::ReceiveEvent event = decoder.feed(rest, &used);
      rest = rest.subview(used, rest.size - used);
      if (event.kind != protocol::ReceiveKind::kMessage) continue;
      std::optional<std::vector<uint8_t>> reply;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        reply = responder_.answer(event.message, monotonic_now_ns());
      }
      if (!reply) continue;
      uint8_t frame[protocol::kUartMaxFrameSize];
      const auto size = protocol::encode_uart_frame(protocol::ByteView{reply->data(), reply->size()}, frame,
                                                    sizeof(frame));
      if (!size) continue;
      size_t at = 0;
      while (at < *size) {
        const ssize_t w = write(fd_, frame + at, *size - at);
        if (w > 0) at += static_cast<size_t>(w);
        else if (w < 0 && errno != EAGAIN && errno != EINTR) break;
      }
    }
  }
}

}  // namespace tetrapulse::host::testing
