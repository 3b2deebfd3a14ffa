#pragma once
// What the code player plays: for each marker a code on a time base (SPEC.md §9: bit n
// occupies rig times [epoch + n T, epoch + (n+1) T), code bit n mod L) and the duty of a
// 1 and a 0 bit. A Config becomes one (program_from_config); so does each Identify pattern.
#include <array>
#include <cstdint>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/request_messages.hpp"
#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::fw {

struct LedProgram {
  // length 0: the marker stays at one_duty.
  std::array<protocol::Code, protocol::kMarkersPerTarget> codes{};
  protocol::TimeBase timebase{0, 1};  // bit period 1 ns until a configuration or pattern sets it
  std::array<uint16_t, protocol::kMarkersPerTarget> one_duty{};
  std::array<uint16_t, protocol::kMarkersPerTarget> zero_duty{};

  // Duty of marker m during bit number n (any integer n).
  uint16_t duty(size_t m, int64_t n) const;
};

// The ceiling Config.current_limit_ma puts on duty, against the board's full-scale
// current: 65535 * limit / full_scale (no ceiling for limit 0 or limit >= full scale).
uint16_t duty_ceiling(uint16_t current_limit_ma, uint16_t full_scale_ma);

// Config -> program: a 1 bit plays brightness, a 0 bit brightness*low_level/65535
// (two_level) or 0 (on_off); constant modulation, and markers without a code, play
// brightness always; every duty capped at `ceiling`.
LedProgram program_from_config(const protocol::Config& config, uint16_t ceiling);

// Identify patterns, starting at rig time `start_ns`, at full duty capped by `ceiling`:
//   blink all: every marker 250 ms on, 250 ms off;
//   chase: marker i on for 200 ms in turn, 0..3;
//   count: marker i blinks i+1 times (150 ms on, 150 ms off), then a pause, every 1.8 s.
LedProgram identify_program(protocol::IdentifyPattern pattern, int64_t start_ns, uint16_t ceiling);

}  // namespace tetrapulse::fw
