#pragma once
// Numbers in messages: shortest form that reads back to six significant digits.
#include <sstream>
#include <string>

namespace tetrapulse::hardware {

inline std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace tetrapulse::hardware
