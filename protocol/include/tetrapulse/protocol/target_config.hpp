#pragma once
// The configuration a target's board plays, from the rig's targets (targets.yaml,
// docs/rig-dataset.md): the one translation from the code model to a board, used by
// the host (`tetrapulse codebook`, the virtual rig's boards) and the simulator alike.
#include <array>
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/code.hpp"
#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::protocol {

// CAN node id of the board of a rig's `index`-th target (0-based, targets.yaml order):
// 1..254 in target order; ids repeat past 254 targets, so give each bus its own.
constexpr uint8_t target_node_id(size_t index) { return static_cast<uint8_t>(1 + index % 254); }

// default_config() with the target's id and four codes (length 0: none), the rig's
// modulation (low_level = round(low * 65535) for two_level only; the default otherwise,
// which on_off and constant ignore), bit period and epoch (rig-time ns), `sync`, and
// target_node_id(index). A time base whose bit period does not fit 32 bits is the
// caller's to reject (validate() does).
Config target_config(uint16_t target_id, const std::array<Code, kMarkersPerTarget>& codes,
                     const ModulationLevels& modulation, const TimeBase& timebase, size_t index, SyncSource sync);

}  // namespace tetrapulse::protocol
