#pragma once
// The board configuration: what SetConfig carries, ConfigReport returns and flash stores
// (SPEC.md §2.5). Times are integer nanoseconds of rig time.
#include <array>
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/code.hpp"  // Code, Modulation: the one code model
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

enum class SyncSource : uint8_t {
  kNone = 0,  // free-running on the local clock
  kGpio = 1,  // edges on the sync input (camera strobe or trigger)
  kCan = 2,   // Sync/FollowUp broadcasts
};

enum class GpioEdge : uint8_t { kRising = 0, kFalling = 1 };

// How a board numbers the sync edge it just saw (k in gpio_edge_epoch_ns + k * period).
enum class GpioEdgeNumbering : uint8_t {
  kNearestCoarseTime = 0,  // k = the integer nearest to the board's coarse rig time (from FollowUp)
  kCountAfterGap = 1,      // k = 0 at the first edge after a gap of at least 2 periods, then +1 per edge
};

// Shortest bit period and sync edge interval a board must accept (10 us).
constexpr uint32_t kMinBitPeriodNs = 10'000;
constexpr uint32_t kMinGpioEdgePeriodNs = 10'000;

// Field order is wire order. The defaults are default_config().
struct Config {
  uint8_t node_id = 1;                         // CAN node id, 1..254
  uint16_t target_id = 0;                      // which target this board drives (codebook id)
  std::array<Code, kMarkersPerTarget> codes{};  // per marker 0..3
  Modulation modulation = Modulation::kOnOff;
  uint16_t low_level = 19'661;                 // emission in a 0 bit, x/65535 of full (two_level only)
  uint32_t bit_period_ns = 10'000'000;         // T >= kMinBitPeriodNs
  int64_t epoch_ns = 0;                        // rig time at which bit 0 starts
  uint16_t brightness = 65'535;                // emission of a 1 bit, x/65535 of full
  uint16_t current_limit_ma = 0;               // LED current ceiling, mA; 0 = the board's hardware maximum
  SyncSource sync_source = SyncSource::kNone;
  GpioEdge gpio_edge = GpioEdge::kRising;
  uint32_t gpio_edge_period_ns = 33'333'333;   // nominal interval between sync edges, >= kMinGpioEdgePeriodNs
  int64_t gpio_edge_epoch_ns = 0;              // edge k happens at rig time gpio_edge_epoch_ns + k * period
  GpioEdgeNumbering gpio_edge_numbering = GpioEdgeNumbering::kNearestCoarseTime;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("node_id", m.node_id);
    io.field("target_id", m.target_id);
    io.field("codes", m.codes);
    io.field("modulation", m.modulation);
    io.field("low_level", m.low_level);
    io.field("bit_period_ns", m.bit_period_ns);
    io.field("epoch_ns", m.epoch_ns);
    io.field("brightness", m.brightness);
    io.field("current_limit_ma", m.current_limit_ma);
    io.field("sync_source", m.sync_source);
    io.field("gpio_edge", m.gpio_edge);
    io.field("gpio_edge_period_ns", m.gpio_edge_period_ns);
    io.field("gpio_edge_epoch_ns", m.gpio_edge_epoch_ns);
    io.field("gpio_edge_numbering", m.gpio_edge_numbering);
  }
};

// Encoded size of a Config (SPEC.md §2.5).
constexpr size_t kConfigSize = 73;

// The configuration of a board fresh from the factory (or after FactoryReset).
constexpr Config default_config() { return Config{}; }

// kBadValue when a field is outside its range (SPEC.md §2.5); used by encode and decode.
Status validate(const Config& config);

// The Config on its own (flash records): validated, then kConfigSize bytes appended.
Status encode_config(const Config& config, ByteWriter& out);
// Exactly kConfigSize bytes: kTruncated, kBadValue or kTrailingBytes otherwise.
Result<Config> decode_config(ByteView in);

}  // namespace tetrapulse::protocol
