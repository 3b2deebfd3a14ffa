#pragma once
// Long-running commands (sync, status --watch) stop cleanly on SIGINT or SIGTERM: the
// handler only sets a flag that their loops check.
#include <atomic>

namespace tetrapulse::cli {

// Installs the handlers (once) and returns the flag they set.
const std::atomic<bool>& stop_on_signals();

}  // namespace tetrapulse::cli
