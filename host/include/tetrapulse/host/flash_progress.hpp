#pragma once
// Progress of a firmware update (over the protocol or USB DFU), for progress bars.
#include <atomic>
#include <cstdint>
#include <functional>

namespace tetrapulse::host {

struct FlashProgress {
  const char* stage = "";  // "begin", "write", "verify", "reboot", "detach", "download", "manifest", "reconnect"
  uint64_t done = 0;       // bytes (write, download) or steps
  uint64_t total = 0;
};

using FlashProgressCallback = std::function<void(const FlashProgress&)>;

// Set by the caller (a signal handler, another thread) to stop an update between steps;
// the update then aborts cleanly and returns kCancelled.
using CancelFlag = std::atomic<bool>;

}  // namespace tetrapulse::host
