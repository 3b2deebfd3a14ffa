#pragma once
// A board's configuration as a YAML file: the fields of protocol/SPEC.md §2.5 under their
// protocol names, enumerations by name and codes as '0'/'1' strings. `tetrapulse codebook`
// writes one per target; `tetrapulse config --file` applies one; `tetrapulse config --show`
// prints one.
//
//   node_id: 3
//   target_id: 7
//   codes: ["1101001110", "1011100100", "0111010011", ""]   # marker 0..3; "" = no code
//   modulation: two_level          # on_off | two_level | constant
//   low_level: 19661               # 0-bit emission x/65535 (two_level)
//   bit_period_ns: 10000000
//   epoch_ns: 0
//   brightness: 65535              # 1-bit emission x/65535
//   current_limit_ma: 0            # 0 = the board's hardware maximum
//   sync_source: can               # none | gpio | can
//   gpio_edge: rising              # rising | falling
//   gpio_edge_period_ns: 33333333
//   gpio_edge_epoch_ns: 0
//   gpio_edge_numbering: nearest_coarse_time   # | count_after_gap
//
// A field left out keeps the §2.5 default; an unknown field is an error (a typo would
// otherwise pass unnoticed).
#include <string>

#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::host {

// The file text, with a header comment line per entry of `header` (may be empty).
std::string format_board_config_yaml(const protocol::Config& config, const std::string& header = "");

// kBadFile naming the file, line and field.
HostResult<protocol::Config> parse_board_config_yaml(const std::string& text, const std::string& name);
HostResult<protocol::Config> read_board_config_yaml(const std::string& path);

}  // namespace tetrapulse::host
