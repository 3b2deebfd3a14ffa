#pragma once
// The words a person uses for board configuration values (protocol/SPEC.md §2.5), shared
// by board configuration files and command-line options: enumerations by name, codes as
// '0'/'1' strings (character i = bit i, as in targets.yaml).
#include <optional>
#include <string>

#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::host {

const char* modulation_name(protocol::Modulation m);        // on_off | two_level | constant
const char* sync_source_name(protocol::SyncSource s);       // none | gpio | can
const char* gpio_edge_name(protocol::GpioEdge e);           // rising | falling
const char* gpio_edge_numbering_name(protocol::GpioEdgeNumbering n);  // nearest_coarse_time | count_after_gap

std::optional<protocol::Modulation> parse_modulation(const std::string& text);
std::optional<protocol::SyncSource> parse_sync_source(const std::string& text);
std::optional<protocol::GpioEdge> parse_gpio_edge(const std::string& text);
std::optional<protocol::GpioEdgeNumbering> parse_gpio_edge_numbering(const std::string& text);

// "1101001110"; "" for length 0 (no code: the marker emits constantly).
std::string code_text(const protocol::Code& code);
// The reverse; "" and "-" are length 0. nullopt with `why` set for anything but 0..64 of '0'/'1'.
std::optional<protocol::Code> parse_code(const std::string& text, std::string* why);

}  // namespace tetrapulse::host
