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

// How a marker stands out from what is behind it (docs/rig-dataset.md):
// brighter (LEDs, lit or reflective balls) or darker (painted balls on a lit floor).
enum class Appearance : uint8_t { kLight, kDark };

// A marker's colour as chroma about grey, in 8-bit levels: u = Cb - 128,
// v = Cr - 128 (BT.601, OpenCV's YCrCb). Only its direction matters to the
// localizer: blends with a grey background lie on the line from grey to it.
struct MarkerColour {
  double u = 0;
  double v = 0;
  std::string name;  // the named colour it came from ("" for u/v given as numbers)
};

// The chroma of a named colour (red, green, blue, yellow, cyan, magenta,
// orange, purple); nullopt for any other name.
std::optional<MarkerColour> named_colour(const std::string& name);
// The named colours, for messages: "red, green, ...".
std::string named_colour_list();

struct Marker {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::optional<Code> code;  // none: emits constantly
  Appearance appearance = Appearance::kLight;
  std::optional<MarkerColour> colour;  // none: seen in grey levels only
};

struct Target {
  int id = 0;
  std::string name;
  double marker_diameter_m = 0;
  // Defaults of the markers that do not say their own (targets.yaml).
  Appearance appearance = Appearance::kLight;
  std::optional<MarkerColour> colour;
  std::array<Marker, 4> markers;

  // The four markers' codes as a board carries them (length 0: no code).
  std::array<Code, 4> codes() const;
};

struct TargetsFile {
  Timebase timebase;
  Modulation modulation;
  std::vector<Target> targets;

  const Target* find(int id) const;
  // Whether some marker has a colour: its images must be read in colour.
  bool needs_colour() const;
};

}  // namespace tetrapulse
