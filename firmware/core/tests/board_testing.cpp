#include "board_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tetrapulse::fw::testing {

protocol::Config edge_rich_config(uint32_t bit_period_ns, int64_t epoch_ns) {
  protocol::Config c = protocol::default_config();
  c.bit_period_ns = bit_period_ns;
  c.epoch_ns = epoch_ns;
  c.codes[0] = protocol::Code{2, 0b01};        // "10"
  c.codes[1] = protocol::Code{4, 0b0011};      // "1100"
  c.codes[2] = protocol::Code{10, 0x1CB};      // "1101001110"
  c.codes[3] = protocol::Code{5, 0b01101};     // "10110"
  return c;
}

TestBoard::TestBoard(const sim_board::SimBoardOptions& options) : board(options), host(board) {}

protocol::Message TestBoard::request(const protocol::Body& body, LinkKind link) {
  protocol::Message m{++seq, body};
  const protocol::Result<protocol::Message> answer = host.request(link, m);
  EXPECT_TRUE(answer.ok()) << "no answer to message type " << static_cast<int>(m.type());
  if (!answer) return protocol::Message{};
  return *answer;
}

void TestBoard::configure(const protocol::Config& config) {
  const protocol::Message answer = request(protocol::SetConfig{config});
  ASSERT_NE(answer.get<protocol::Ack>(), nullptr) << "SetConfig refused";
}

EdgeTiming edge_timing(const sim_board::SimBoard& board, const protocol::TimeBase& tb, int64_t from_ns,
                       int64_t to_ns, size_t* off_edge) {
  EdgeTiming t;
  double sum = 0, sum2 = 0;
  size_t off = 0;
  for (const sim_board::AppliedLedChange& c : board.leds().log()) {
    if (c.rig_ns < from_ns || c.rig_ns >= to_ns) continue;
    const long double rel = c.rig_ns - static_cast<long double>(tb.epoch_ns);
    const long double n = std::round(rel / static_cast<long double>(tb.bit_period_ns));
    const double err = static_cast<double>(rel - n * static_cast<long double>(tb.bit_period_ns));
    if (std::fabs(err) > static_cast<double>(tb.bit_period_ns) / 4) {
      ++off;
      continue;
    }
    ++t.count;
    sum += err;
    sum2 += err * err;
    t.max_abs_ns = std::max(t.max_abs_ns, std::fabs(err));
  }
  if (t.count > 0) {
    t.mean_ns = sum / static_cast<double>(t.count);
    t.rms_ns = std::sqrt(sum2 / static_cast<double>(t.count));
  }
  if (off_edge != nullptr) *off_edge = off;
  return t;
}

std::vector<long double> change_times(const sim_board::SimBoard& board, uint8_t m, int64_t from_ns, int64_t to_ns) {
  std::vector<long double> out;
  for (const sim_board::AppliedLedChange& c : board.leds().log(m)) {
    if (c.rig_ns >= from_ns && c.rig_ns < to_ns) out.push_back(c.rig_ns);
  }
  return out;
}

}  // namespace tetrapulse::fw::testing
