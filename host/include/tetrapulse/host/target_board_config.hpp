#pragma once
// The configuration a target's board plays, from targets.yaml (docs/rig-dataset.md):
// protocol::target_config (target_config.hpp) of the file's index-th target. `tetrapulse
// codebook` writes it per target; the virtual rig configures its boards with it.
#include <cstddef>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::host {

// `index` < file.targets.size().
protocol::Config target_board_config(const TargetsFile& file, size_t index, protocol::SyncSource sync);

}  // namespace tetrapulse::host
