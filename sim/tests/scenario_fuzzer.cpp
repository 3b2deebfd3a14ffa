// libFuzzer: any bytes given to the scenario reader give a scenario or a located error, never a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "tetrapulse/sim/scenario_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto s = tetrapulse::sim::parse_scenario(text, "fuzz.yaml");
  if (!s && s.error().message.empty()) __builtin_trap();
  return 0;
}
