#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

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

}  // namespace tetrapulse
