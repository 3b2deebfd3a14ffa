#pragma once
// Test support: a simulated board and its host port, configured through the real command
// handler, plus measures of LED edge timing against the ideal bit edges (SPEC.md §9).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/timebase.hpp"
#include "tetrapulse/sim_board/host_port.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::fw::testing {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kSecond = 1'000'000'000;

// Four square-wave-ish codes with many edges, bit period `bit_period_ns`, on_off.
protocol::Config edge_rich_config(uint32_t bit_period_ns, int64_t epoch_ns = 0);

struct TestBoard {
  explicit TestBoard(const sim_board::SimBoardOptions& options);
  sim_board::SimBoard board;
  sim_board::HostPort host;
  uint8_t seq = 0;

  // A request over USB; the decoded answer (fails the test when none).
  protocol::Message request(const protocol::Body& body, LinkKind link = LinkKind::kUsb);
  // SetConfig, expecting an Ack.
  void configure(const protocol::Config& config);
  protocol::SyncState sync_state() { return board.status().sync_state; }
};

struct EdgeTiming {
  size_t count = 0;      // code edges compared
  double max_abs_ns = 0; // largest |applied - ideal|
  double mean_ns = 0;
  double rms_ns = 0;
};

// Applied LED changes with true rig time in [from_ns, to_ns), each against the nearest bit
// edge of `tb` (a change more than a quarter bit from any edge is not a code edge and is
// counted in `off_edge` instead).
EdgeTiming edge_timing(const sim_board::SimBoard& board, const protocol::TimeBase& tb, int64_t from_ns,
                       int64_t to_ns, size_t* off_edge = nullptr);

// Applied change times of marker `m` in [from, to) (true rig ns).
std::vector<long double> change_times(const sim_board::SimBoard& board, uint8_t m, int64_t from_ns, int64_t to_ns);

}  // namespace tetrapulse::fw::testing
