#pragma once
// Target geometry, codes and time base: the contents of a rig dataset's
// targets.yaml (spec/rig-dataset.md). Positions in metres, target frame.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace tetrapulse {

// A '0'/'1' code played cyclically, bit i = character i. At most 64 bits
// (the boards' limit, protocol/SPEC.md).
struct Code {
  uint64_t bits = 0;     // bit i set = character i is '1'
  uint32_t length = 0;   // 1..64

  bool bit(uint32_t i) const { return (bits >> (i % length)) & 1u; }
  std::string str() const;
  // Parses "1101…"; nullopt with `why` filled on anything else.
  static std::optional<Code> parse(const std::string& text, std::string* why);
  bool operator==(const Code& o) const { return bits == o.bits && length == o.length; }
};

struct Marker {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::optional<Code> code;  // none: emits constantly
};

struct Target {
  int id = 0;
  std::string name;
  double marker_diameter_m = 0;
  std::array<Marker, 4> markers;
};

enum class ModulationKind { kOnOff, kTwoLevel, kConstant };
const char* modulation_kind_name(ModulationKind kind);

struct Modulation {
  ModulationKind kind = ModulationKind::kOnOff;
  double low = 0.0;  // relative emission in a 0 bit (two_level only), [0, 1)
};

struct Timebase {
  bool synchronized = true;
  int64_t epoch_ns = 0;
  int64_t bit_period_ns = 10'000'000;
};

struct TargetsFile {
  Timebase timebase;
  Modulation modulation;
  std::vector<Target> targets;

  const Target* find(int id) const;
};

}  // namespace tetrapulse
