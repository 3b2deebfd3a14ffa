#pragma once
// Local time on a board: ticks of its free-running counter, extended to 64 bits.
#include <cstdint>

namespace tetrapulse::fw {

// A count of local counter ticks since the counter started (never wraps in practice:
// 2^64 ticks at 168 MHz is 3500 years).
using Tick = uint64_t;

}  // namespace tetrapulse::fw
