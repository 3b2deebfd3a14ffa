#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

namespace {

struct NamedColour {
  const char* name;
  double r, g, b;  // linear-ish sRGB of a saturated paint or LED, 0..1
};

constexpr NamedColour kNamedColours[] = {
    {"red", 1, 0, 0},      {"green", 0, 1, 0},   {"blue", 0, 0, 1},        {"yellow", 1, 1, 0},
    {"cyan", 0, 1, 1},     {"magenta", 1, 0, 1}, {"orange", 1, 0.5, 0},    {"purple", 0.5, 0, 1},
};

}  // namespace

std::optional<MarkerColour> named_colour(const std::string& name) {
  for (const NamedColour& c : kNamedColours) {
    if (name != c.name) continue;
    // BT.601 as OpenCV's BGR2YCrCb: Cr = (R - Y) 0.713, Cb = (B - Y) 0.564, in 8-bit levels.
    const double y = 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
    return MarkerColour{255.0 * 0.564 * (c.b - y), 255.0 * 0.713 * (c.r - y), name};
  }
  return std::nullopt;
}

std::string named_colour_list() {
  std::string out;
  for (const NamedColour& c : kNamedColours) out += (out.empty() ? "" : ", ") + std::string(c.name);
  return out;
}

std::string code_text(const Code& code) {
  std::string s(code.length, '0');
  for (uint32_t i = 0; i < code.length; ++i) s[i] = code.bit(i) ? '1' : '0';
  return s;
}

std::optional<Code> parse_code(const std::string& text, std::string* why) {
  if (text.empty() || text.size() > 64) {
    if (why) *why = "must have 1 to 64 bits, has " + std::to_string(text.size());
    return std::nullopt;
  }
  Code c;
  c.length = static_cast<uint8_t>(text.size());
  for (uint32_t i = 0; i < c.length; ++i) {
    if (text[i] == '1') {
      c.bits |= uint64_t{1} << i;
    } else if (text[i] != '0') {
      if (why) *why = "character " + std::to_string(i + 1) + " is '" + std::string(1, text[i]) + "', not 0 or 1";
      return std::nullopt;
    }
  }
  return c;
}

std::array<Code, 4> Target::codes() const {
  std::array<Code, 4> out{};
  for (size_t k = 0; k < markers.size(); ++k) out[k] = markers[k].code.value_or(Code{});
  return out;
}

const Target* TargetsFile::find(int id) const {
  for (const Target& t : targets) {
    if (t.id == id) return &t;
  }
  return nullptr;
}

bool TargetsFile::needs_colour() const {
  for (const Target& t : targets) {
    for (const Marker& m : t.markers) {
      if (m.colour) return true;
    }
  }
  return false;
}

}  // namespace tetrapulse
