#include "tetrapulse/host/target_board_config.hpp"

#include <cmath>

#include "tetrapulse/protocol/can_id.hpp"

namespace tetrapulse::host {

protocol::Config target_board_config(const TargetsFile& file, size_t index, protocol::SyncSource sync) {
  const Target& t = file.targets[index];
  protocol::Config c = protocol::default_config();
  c.node_id = static_cast<uint8_t>(index % protocol::kCanLastBoardNode + 1);
  c.target_id = static_cast<uint16_t>(t.id);
  for (size_t k = 0; k < t.markers.size() && k < c.codes.size(); ++k) {
    if (t.markers[k].code) c.codes[k] = protocol::Code{static_cast<uint8_t>(t.markers[k].code->length), t.markers[k].code->bits};
  }
  c.modulation = file.modulation.kind == ModulationKind::kTwoLevel ? protocol::Modulation::kTwoLevel
                 : file.modulation.kind == ModulationKind::kConstant ? protocol::Modulation::kConstant
                                                                      : protocol::Modulation::kOnOff;
  if (c.modulation == protocol::Modulation::kTwoLevel) {
    c.low_level = static_cast<uint16_t>(std::lround(file.modulation.low * 65535.0));
  }
  c.bit_period_ns = static_cast<uint32_t>(file.timebase.bit_period_ns);
  c.epoch_ns = file.timebase.epoch_ns;
  c.sync_source = sync;
  return c;
}

}  // namespace tetrapulse::host
