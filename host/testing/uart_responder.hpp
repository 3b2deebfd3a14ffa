#pragma once
// A BoardResponder on the board's end of a byte stream (the master side of a pty), on its
// own thread: decodes UART frames with the protocol's decoder and answers each message.
#include <atomic>
#include <mutex>
#include <thread>

#include "board_responder.hpp"

namespace tetrapulse::host::testing {

class UartResponder {
 public:
  UartResponder(int fd, ResponderIdentity identity = {});
  ~UartResponder();  // stops the thread

  // Runs `f(responder)` with the thread held off.
  template <class F>
  auto with_responder(F&& f) {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(responder_);
  }

 private:
  void run();

  int fd_;
  BoardResponder responder_;
  std::mutex mutex_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace tetrapulse::host::testing
