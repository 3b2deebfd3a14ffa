#pragma once
// The one model of codes and their modulation (SPEC.md §2.5, §8.5), shared by the
// boards, the host, the simulator and the localizer. Header only and freestanding
// (no heap, no exceptions, no OS): the localizer may include it without the rest
// of protocol/.
#include <cstdint>

namespace tetrapulse::protocol {

// Longest code a board plays (bits).
constexpr uint32_t kMaxCodeLength = 64;

// One marker's code, played cyclically: bit i (LSB first) is character i of the
// code string "1101...". length 0 means no code: the marker emits constantly.
struct Code {
  uint8_t length = 0;  // 0, or 1..kMaxCodeLength
  uint64_t bits = 0;   // bits at positions >= length are 0

  // Bit i mod length (false for no code): callers index the cycle freely.
  constexpr bool bit(uint32_t i) const { return length != 0 && ((bits >> (i % length)) & 1u) != 0; }
  constexpr bool operator==(const Code& o) const { return length == o.length && bits == o.bits; }
  constexpr bool operator!=(const Code& o) const { return !(*this == o); }

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("length", m.length);
    io.field("bits", m.bits);
  }
};

// How a board emits the bits of its codes.
enum class Modulation : uint8_t {
  kOnOff = 0,     // 1 bit: full emission, 0 bit: dark
  kTwoLevel = 1,  // 1 bit: full emission, 0 bit: low_level
  kConstant = 2,  // codes ignored, markers lit constantly
};
constexpr int kModulationCount = 3;

// The names configuration files and the command line use (targets.yaml `modulation.kind`,
// board configuration YAML `modulation`).
constexpr const char* modulation_name(Modulation m) {
  switch (m) {
    case Modulation::kOnOff: return "on_off";
    case Modulation::kTwoLevel: return "two_level";
    case Modulation::kConstant: return "constant";
  }
  return "unknown";
}

// The modulation named `text` (NUL-terminated); false when none is.
constexpr bool modulation_from_name(const char* text, Modulation* out) {
  for (int k = 0; k < kModulationCount; ++k) {
    const char* name = modulation_name(static_cast<Modulation>(k));
    int i = 0;
    while (name[i] != '\0' && text[i] == name[i]) ++i;
    if (name[i] == '\0' && text[i] == '\0') {
      *out = static_cast<Modulation>(k);
      return true;
    }
  }
  return false;
}

// A rig's modulation: its kind and, for two_level, a 0 bit's emission relative to a
// 1 bit's, in [0, 1) (targets.yaml `modulation.low`; boards carry it as low_level/65535).
struct ModulationLevels {
  Modulation kind = Modulation::kOnOff;
  double low = 0.0;
};

// A frequency code (SPEC.md §8.5): `ones` 1 bits, then `length - ones` 0 bits.
struct SquareWave {
  uint8_t length = 2;  // bits per period, 2..64
  uint8_t ones = 1;    // 1 bits first, 1..length-1
};

// The word of a square wave: bits 0..ones-1 set (the string "1..10..0").
constexpr uint64_t square_wave_word(SquareWave wave) {
  return wave.ones >= 64 ? ~uint64_t{0} : (uint64_t{1} << wave.ones) - 1;
}

// Whether `code` is a square wave under some rotation: exactly one cyclic run of 1s
// and one of 0s (a frequency code, not a binary one). Fills *wave (when not null).
constexpr bool is_square_wave(const Code& code, SquareWave* wave = nullptr) {
  if (code.length < 2 || code.length > kMaxCodeLength) return false;
  uint32_t rises = 0;  // 0 -> 1 steps around the cycle: one for "1..10..0", none for a constant
  uint32_t ones = 0;
  for (uint32_t i = 0; i < code.length; ++i) {
    rises += (!code.bit(i) && code.bit(i + 1)) ? 1u : 0u;
    ones += code.bit(i) ? 1u : 0u;
  }
  if (rises != 1) return false;
  if (wave != nullptr) *wave = SquareWave{code.length, static_cast<uint8_t>(ones)};
  return true;
}

}  // namespace tetrapulse::protocol
