// Board configuration files: every valid configuration survives writing and reading back,
// fields left out keep the defaults, and each kind of mistake is refused naming the line.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "tetrapulse/host/board_config_yaml.hpp"

namespace tetrapulse::host {
namespace {

using protocol::Config;

std::vector<uint8_t> bytes_of(const Config& c) {
  std::vector<uint8_t> out(protocol::kConfigSize);
  protocol::ByteWriter w(out.data(), out.size());
  EXPECT_TRUE(protocol::encode_config(c, w));
  return out;
}

Config random_config() {
  Config c;
  c.node_id = *rc::gen::inRange<uint8_t>(1, 255);
  c.target_id = *rc::gen::arbitrary<uint16_t>();
  for (auto& code : c.codes) {
    code.length = *rc::gen::inRange<uint8_t>(0, 65);
    const uint64_t bits = *rc::gen::arbitrary<uint64_t>();
    code.bits = code.length == 64 ? bits : bits & ((uint64_t{1} << code.length) - 1);
  }
  c.modulation = static_cast<protocol::Modulation>(*rc::gen::inRange(0, 3));
  c.low_level = *rc::gen::arbitrary<uint16_t>();
  c.bit_period_ns = *rc::gen::inRange<uint32_t>(protocol::kMinBitPeriodNs, UINT32_MAX);
  c.epoch_ns = *rc::gen::arbitrary<int64_t>();
  c.brightness = *rc::gen::arbitrary<uint16_t>();
  c.current_limit_ma = *rc::gen::arbitrary<uint16_t>();
  c.sync_source = static_cast<protocol::SyncSource>(*rc::gen::inRange(0, 3));
  c.gpio_edge = static_cast<protocol::GpioEdge>(*rc::gen::inRange(0, 2));
  c.gpio_edge_period_ns = *rc::gen::inRange<uint32_t>(protocol::kMinGpioEdgePeriodNs, UINT32_MAX);
  c.gpio_edge_epoch_ns = *rc::gen::arbitrary<int64_t>();
  c.gpio_edge_numbering = static_cast<protocol::GpioEdgeNumbering>(*rc::gen::inRange(0, 2));
  return c;
}

RC_GTEST_PROP(BoardConfigYaml, EveryValidConfigRoundTrips, ()) {
  const Config c = random_config();
  RC_PRE(protocol::validate(c).ok());
  auto back = parse_board_config_yaml(format_board_config_yaml(c, "target 7\nwritten by a test"), "t.yaml");
  RC_ASSERT(back.has_value());
  RC_ASSERT(bytes_of(*back) == bytes_of(c));
}

TEST(BoardConfigYaml, FieldsLeftOutKeepTheDefaults) {
  auto c = parse_board_config_yaml("target_id: 5\ncodes: [\"1100\", \"\", \"-\", \"1\"]\nsync_source: gpio\n", "b.yaml");
  ASSERT_TRUE(c) << c.error().what();
  Config expected = protocol::default_config();
  expected.target_id = 5;
  expected.codes[0] = protocol::Code{4, 0x3};
  expected.codes[3] = protocol::Code{1, 0x1};
  expected.sync_source = protocol::SyncSource::kGpio;
  EXPECT_EQ(bytes_of(*c), bytes_of(expected));
}

TEST(BoardConfigYaml, MistakesAreRefusedWithFileLineAndField) {
  struct Case {
    const char* text;
    const char* error;
  };
  for (const Case& k : {
           Case{"node_id: 0\n", "b.yaml:1: node_id: 0 is outside 1..254"},
           Case{"target_id: 7\nnode: 3\n", "b.yaml:2: node: not a board configuration field"},
           Case{"codes: [\"1101\", \"10x1\", \"\", \"\"]\n", "b.yaml:1: codes[1]: '10x1' character 3 is 'x', not 0 or 1"},
           Case{"codes: [\"1101\"]\n", "b.yaml:1: codes: expected a list of 4 code strings (marker 0..3)"},
           Case{"modulation: pwm\n", "b.yaml:1: modulation: 'pwm' is not one of on_off, two_level, constant"},
           Case{"bit_period_ns: 5\n", "b.yaml:1: bit_period_ns: 5 is outside 10000..4294967295"},
           Case{"brightness: 70000\n", "b.yaml:1: brightness: 70000 is outside 0..65535"},
           Case{"epoch_ns: soon\n", "b.yaml:1: epoch_ns: expected an integer, got 'soon'"},
           Case{"- a list\n", "b.yaml: expected a YAML mapping at the top level"},
       }) {
    auto c = parse_board_config_yaml(k.text, "b.yaml");
    ASSERT_FALSE(c) << k.text;
    EXPECT_EQ(c.error().kind, HostErrorKind::kBadFile);
    EXPECT_EQ(c.error().what(), k.error);
  }
  auto missing = read_board_config_yaml("/nonexistent/board.yaml");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, HostErrorKind::kBadFile);
  EXPECT_NE(missing.error().what().find("/nonexistent/board.yaml"), std::string::npos);
}

}  // namespace
}  // namespace tetrapulse::host
