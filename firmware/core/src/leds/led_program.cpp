#include "tetrapulse/fw/leds/led_program.hpp"

#include "tetrapulse/fw/leds/led_driver.hpp"

namespace tetrapulse::fw {
namespace {

constexpr int64_t kMs = 1'000'000;

uint16_t cap(uint32_t duty, uint16_t ceiling) { return static_cast<uint16_t>(duty < ceiling ? duty : ceiling); }

protocol::Code code_of(uint8_t length, uint64_t bits) {
  protocol::Code c;
  c.length = length;
  c.bits = bits;
  return c;
}

}  // namespace

uint16_t LedProgram::duty(size_t m, int64_t n) const {
  const protocol::Code& code = codes[m];
  if (code.length == 0) return one_duty[m];
  const auto index = static_cast<uint32_t>(protocol::floor_mod(n, code.length));
  return code.bit(index) ? one_duty[m] : zero_duty[m];
}

uint16_t duty_ceiling(uint16_t current_limit_ma, uint16_t full_scale_ma) {
  if (current_limit_ma == 0 || full_scale_ma == 0 || current_limit_ma >= full_scale_ma) return kDutyFull;
  return static_cast<uint16_t>(uint32_t{kDutyFull} * current_limit_ma / full_scale_ma);
}

LedProgram program_from_config(const protocol::Config& config, uint16_t ceiling) {
  LedProgram p;
  p.timebase = protocol::TimeBase{config.epoch_ns, static_cast<int64_t>(config.bit_period_ns)};
  const uint32_t one = config.brightness;
  uint32_t zero = 0;
  if (config.modulation == protocol::Modulation::kTwoLevel) {
    zero = (one * config.low_level + kDutyFull / 2) / kDutyFull;
  }
  for (size_t m = 0; m < protocol::kMarkersPerTarget; ++m) {
    p.codes[m] = config.modulation == protocol::Modulation::kConstant ? protocol::Code{} : config.codes[m];
    p.one_duty[m] = cap(one, ceiling);
    p.zero_duty[m] = cap(zero, ceiling);
  }
  return p;
}

LedProgram identify_program(protocol::IdentifyPattern pattern, int64_t start_ns, uint16_t ceiling) {
  LedProgram p;
  p.timebase.epoch_ns = start_ns;
  for (size_t m = 0; m < protocol::kMarkersPerTarget; ++m) {
    p.one_duty[m] = ceiling;
    p.zero_duty[m] = 0;
    switch (pattern) {
      case protocol::IdentifyPattern::kBlinkAll:
        p.timebase.bit_period_ns = 250 * kMs;
        p.codes[m] = code_of(2, 0b01);
        break;
      case protocol::IdentifyPattern::kChase:
        p.timebase.bit_period_ns = 200 * kMs;
        p.codes[m] = code_of(4, uint64_t{1} << m);
        break;
      case protocol::IdentifyPattern::kCountIndex: {
        // Marker m: m + 1 blinks ("10" each), then dark to the end of 12 bits (1.8 s).
        uint64_t bits = 0;
        for (size_t j = 0; j <= m; ++j) bits |= uint64_t{1} << (2 * j);
        p.timebase.bit_period_ns = 150 * kMs;
        p.codes[m] = code_of(12, bits);
        break;
      }
      case protocol::IdentifyPattern::kStop:
        p.timebase.bit_period_ns = 1;
        break;
    }
  }
  return p;
}

}  // namespace tetrapulse::fw
