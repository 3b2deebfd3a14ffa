#include "tetrapulse/fw/storage/config_store.hpp"

namespace tetrapulse::fw {

StoredConfig load_config(const RecordStore& store) {
  uint8_t buf[protocol::kConfigSize];
  const protocol::Result<size_t> n = store.read(kConfigRecordKey, buf, sizeof(buf));
  if (!n) return StoredConfig{protocol::default_config(), false};
  const protocol::Result<protocol::Config> config = protocol::decode_config(protocol::ByteView{buf, *n});
  if (!config) return StoredConfig{protocol::default_config(), false};
  return StoredConfig{*config, true};
}

protocol::Status save_config(RecordStore& store, const protocol::Config& config) {
  uint8_t buf[protocol::kConfigSize];
  protocol::ByteWriter out(buf, sizeof(buf));
  const protocol::Status encoded = protocol::encode_config(config, out);
  if (!encoded) return encoded;
  return store.write(kConfigRecordKey, out.view());
}

}  // namespace tetrapulse::fw
