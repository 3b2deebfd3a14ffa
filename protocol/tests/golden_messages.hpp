#pragma once
// The messages that protocol/vectors/messages/ holds, built field by field from the
// descriptions in each file, keyed "stem" or "stem.record" ("update_chunk.full").
#include <map>
#include <string>

#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol::testing {

std::map<std::string, Message> golden_messages();

// The key of a record in a vectors file.
std::string golden_key(const std::string& stem, const std::string& record);

}  // namespace tetrapulse::protocol::testing
