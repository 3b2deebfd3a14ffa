#include "tetrapulse/protocol/target_config.hpp"

namespace tetrapulse::protocol {

Config target_config(uint16_t target_id, const std::array<Code, kMarkersPerTarget>& codes,
                     const ModulationLevels& modulation, const TimeBase& timebase, size_t index, SyncSource sync) {
  Config c = default_config();
  c.node_id = target_node_id(index);
  c.target_id = target_id;
  c.codes = codes;
  c.modulation = modulation.kind;
  // low is in [0, 1): adding one half and truncating rounds to nearest, as lround does.
  if (c.modulation == Modulation::kTwoLevel) c.low_level = static_cast<uint16_t>(modulation.low * 65535.0 + 0.5);
  c.bit_period_ns = static_cast<uint32_t>(timebase.bit_period_ns);
  c.epoch_ns = timebase.epoch_ns;
  c.sync_source = sync;
  return c;
}

}  // namespace tetrapulse::protocol
