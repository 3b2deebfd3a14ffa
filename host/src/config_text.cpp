#include "tetrapulse/host/config_text.hpp"

#include <fmt/format.h>

namespace tetrapulse::host {

using protocol::GpioEdge;
using protocol::GpioEdgeNumbering;
using protocol::Modulation;
using protocol::SyncSource;

const char* modulation_name(Modulation m) {
  switch (m) {
    case Modulation::kOnOff: return "on_off";
    case Modulation::kTwoLevel: return "two_level";
    case Modulation::kConstant: return "constant";
  }
  return "unknown";
}

const char* sync_source_name(SyncSource s) {
  switch (s) {
    case SyncSource::kNone: return "none";
    case SyncSource::kGpio: return "gpio";
    case SyncSource::kCan: return "can";
  }
  return "unknown";
}

const char* gpio_edge_name(GpioEdge e) { return e == GpioEdge::kFalling ? "falling" : "rising"; }

const char* gpio_edge_numbering_name(GpioEdgeNumbering n) {
  return n == GpioEdgeNumbering::kCountAfterGap ? "count_after_gap" : "nearest_coarse_time";
}

namespace {

// The enumerator whose name is `text`, trying values 0..count-1.
template <class E, class Name>
std::optional<E> by_name(const std::string& text, int count, Name name) {
  for (int i = 0; i < count; ++i) {
    if (text == name(static_cast<E>(i))) return static_cast<E>(i);
  }
  return std::nullopt;
}

}  // namespace

std::optional<Modulation> parse_modulation(const std::string& t) { return by_name<Modulation>(t, 3, modulation_name); }
std::optional<SyncSource> parse_sync_source(const std::string& t) { return by_name<SyncSource>(t, 3, sync_source_name); }
std::optional<GpioEdge> parse_gpio_edge(const std::string& t) { return by_name<GpioEdge>(t, 2, gpio_edge_name); }
std::optional<GpioEdgeNumbering> parse_gpio_edge_numbering(const std::string& t) {
  return by_name<GpioEdgeNumbering>(t, 2, gpio_edge_numbering_name);
}

std::string code_text(const protocol::Code& code) {
  std::string s(code.length, '0');
  for (uint32_t i = 0; i < code.length; ++i) s[i] = code.bit(i) ? '1' : '0';
  return s;
}

std::optional<protocol::Code> parse_code(const std::string& text, std::string* why) {
  if (text.empty() || text == "-") return protocol::Code{};
  if (text.size() > protocol::kMaxCodeLength) {
    if (why != nullptr) *why = fmt::format("has {} bits; a board plays at most {}", text.size(), protocol::kMaxCodeLength);
    return std::nullopt;
  }
  protocol::Code c;
  c.length = static_cast<uint8_t>(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '1') {
      c.bits |= uint64_t{1} << i;
    } else if (text[i] != '0') {
      if (why != nullptr) *why = fmt::format("character {} is '{}', not 0 or 1", i + 1, text[i]);
      return std::nullopt;
    }
  }
  return c;
}

}  // namespace tetrapulse::host
