#include "tetrapulse/host/target_board_config.hpp"

#include "tetrapulse/protocol/target_config.hpp"

namespace tetrapulse::host {

protocol::Config target_board_config(const TargetsFile& file, size_t index, protocol::SyncSource sync) {
  const Target& t = file.targets[index];
  return protocol::target_config(static_cast<uint16_t>(t.id), t.codes(), file.modulation, file.timebase, index, sync);
}

}  // namespace tetrapulse::host
