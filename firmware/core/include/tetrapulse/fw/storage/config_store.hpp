#pragma once
// The board configuration in the record store (SPEC.md §2.5, the 73-byte encoding).
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::fw {

struct StoredConfig {
  protocol::Config config;
  bool from_flash = false;  // false: nothing stored (or unreadable), the defaults
};

// The stored configuration, or the defaults when none is stored or it does not decode.
StoredConfig load_config(const RecordStore& store);
// Validates and stores `config` (power-loss safe).
protocol::Status save_config(RecordStore& store, const protocol::Config& config);

}  // namespace tetrapulse::fw
