#include "tetrapulse/protocol/config.hpp"

#include "field_io.hpp"

namespace tetrapulse::protocol {
namespace {

bool valid_code(const Code& code) {
  if (code.length > kMaxCodeLength) return false;
  // No bits beyond the code's length (a 64-bit code uses them all).
  return code.length == 64 || (code.bits >> code.length) == 0;
}

}  // namespace

Status validate(const Config& c) {
  if (c.node_id < 1 || c.node_id > 254) return Error::kBadValue;
  for (const Code& code : c.codes) {
    if (!valid_code(code)) return Error::kBadValue;
  }
  if (c.modulation > Modulation::kConstant) return Error::kBadValue;
  if (c.bit_period_ns < kMinBitPeriodNs) return Error::kBadValue;
  if (c.sync_source > SyncSource::kCan) return Error::kBadValue;
  if (c.gpio_edge > GpioEdge::kFalling) return Error::kBadValue;
  if (c.gpio_edge_period_ns < kMinGpioEdgePeriodNs) return Error::kBadValue;
  if (c.gpio_edge_numbering > GpioEdgeNumbering::kCountAfterGap) return Error::kBadValue;
  return {};
}

Status encode_config(const Config& config, ByteWriter& out) {
  if (const Status s = validate(config); !s.ok()) return s;
  return detail::write_fields(out, config);
}

Result<Config> decode_config(ByteView in) {
  ByteReader reader(in);
  Config config;
  const Status s = detail::read_exactly(reader, config, [](const Config& c) { return validate(c); });
  if (!s.ok()) return s.error();
  return config;
}

}  // namespace tetrapulse::protocol
