#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

std::string Code::str() const {
  std::string s(length, '0');
  for (uint32_t i = 0; i < length; ++i) s[i] = bit(i) ? '1' : '0';
  return s;
}

std::optional<Code> Code::parse(const std::string& text, std::string* why) {
  if (text.empty() || text.size() > 64) {
    if (why) *why = "must have 1 to 64 bits, has " + std::to_string(text.size());
    return std::nullopt;
  }
  Code c;
  c.length = static_cast<uint32_t>(text.size());
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

const char* modulation_kind_name(ModulationKind kind) {
  switch (kind) {
    case ModulationKind::kOnOff: return "on_off";
    case ModulationKind::kTwoLevel: return "two_level";
    case ModulationKind::kConstant: return "constant";
  }
  return "on_off";
}

const Target* TargetsFile::find(int id) const {
  for (const Target& t : targets) {
    if (t.id == id) return &t;
  }
  return nullptr;
}

}  // namespace tetrapulse
