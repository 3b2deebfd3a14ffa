#pragma once
// Target geometry, codes and time base: the contents of a rig dataset's
// targets.yaml (docs/rig-dataset.md). Positions in metres, target frame.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/protocol/code.hpp"
#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse {

// Codes, modulation and time base are the one model of protocol/model
// (tetrapulse/protocol/code.hpp, timebase.hpp), under the names the localizer uses.
using Code = protocol::Code;
using ModulationKind = protocol::Modulation;
using Modulation = protocol::ModulationLevels;
using Timebase = protocol::TimeBase;

// A code as text, character i = bit i ("1101..."); "" for no code.
std::string code_text(const Code& code);
// Parses "1101…" (1 to 64 characters); nullopt with `why` filled on anything else.
std::optional<Code> parse_code(const std::string& text, std::string* why);

struct Marker {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::optional<Code> code;  // none: emits constantly
};

struct Target {
  int id = 0;
  std::string name;
  double marker_diameter_m = 0;
  std::array<Marker, 4> markers;

  // The four markers' codes as a board carries them (length 0: no code).
  std::array<Code, 4> codes() const;
};

struct TargetsFile {
  Timebase timebase;
  Modulation modulation;
  std::vector<Target> targets;

  const Target* find(int id) const;
};

}  // namespace tetrapulse
