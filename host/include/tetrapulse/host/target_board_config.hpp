#pragma once
// The configuration a target's board plays, from targets.yaml (spec/rig-dataset.md): the
// target's four codes, the file's time base (epoch and bit period, rig-time ns) and
// modulation, the given sync source, and node ids 1..254 in target order (they repeat past
// 254 targets: give each bus its own). `tetrapulse codebook` writes it per target; the
// virtual rig configures its boards with it.
#include <cstddef>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::host {

// `index` < file.targets.size().
protocol::Config target_board_config(const TargetsFile& file, size_t index, protocol::SyncSource sync);

}  // namespace tetrapulse::host
