#pragma once
// The words a person uses for board configuration values (protocol/SPEC.md §2.5), shared
// by board configuration files and command-line options: enumerations by name, codes as
// '0'/'1' strings (character i = bit i, as in targets.yaml).
#include <optional>
#include <string>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::host {

// on_off | two_level | constant: the code model's names (protocol/model/.../code.hpp).
using protocol::modulation_name;
const char* sync_source_name(protocol::SyncSource s);       // none | gpio | can
const char* gpio_edge_name(protocol::GpioEdge e);           // rising | falling
const char* gpio_edge_numbering_name(protocol::GpioEdgeNumbering n);  // nearest_coarse_time | count_after_gap

std::optional<protocol::Modulation> parse_modulation(const std::string& text);
std::optional<protocol::SyncSource> parse_sync_source(const std::string& text);
std::optional<protocol::GpioEdge> parse_gpio_edge(const std::string& text);
std::optional<protocol::GpioEdgeNumbering> parse_gpio_edge_numbering(const std::string& text);

// "1101001110"; "" for length 0 (no code: the marker emits constantly). As in targets.yaml.
using tetrapulse::code_text;
// The reverse; "" and "-" are length 0 (a board's marker without a code), anything else
// as targets.yaml reads it. nullopt with `why` set for anything but 0..64 of '0'/'1'.
std::optional<protocol::Code> parse_code(const std::string& text, std::string* why);

}  // namespace tetrapulse::host
