#pragma once
// How board answers read on a terminal and in JSON (`--json`).
#include <string>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::cli {

std::string version_text(uint32_t packed);          // "1.2.3"
std::string serial_text(const protocol::Info& info);  // 24 upper-case hex digits
std::string capabilities_text(uint32_t capabilities);  // "usb can gpio-sync ..."

// Several lines, "  field: value", for `info`.
std::string format_info(const std::string& address, const protocol::Info& info);
std::string info_json(const std::string& address, const protocol::Info& info);

// One line for `status` (and each line of `status --watch`).
std::string format_status(const protocol::StatusReport& s);
std::string status_json(const std::string& address, const protocol::StatusReport& s);

std::string config_json(const std::string& address, const protocol::Config& c);

}  // namespace tetrapulse::cli
