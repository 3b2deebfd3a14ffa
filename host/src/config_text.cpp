#include "tetrapulse/host/config_text.hpp"

#include <fmt/format.h>

namespace tetrapulse::host {

using protocol::GpioEdge;
using protocol::GpioEdgeNumbering;
using protocol::Modulation;
using protocol::SyncSource;

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

std::optional<Modulation> parse_modulation(const std::string& t) {
  Modulation m = Modulation::kOnOff;
  if (!protocol::modulation_from_name(t.c_str(), &m)) return std::nullopt;
  return m;
}
std::optional<SyncSource> parse_sync_source(const std::string& t) { return by_name<SyncSource>(t, 3, sync_source_name); }
std::optional<GpioEdge> parse_gpio_edge(const std::string& t) { return by_name<GpioEdge>(t, 2, gpio_edge_name); }
std::optional<GpioEdgeNumbering> parse_gpio_edge_numbering(const std::string& t) {
  return by_name<GpioEdgeNumbering>(t, 2, gpio_edge_numbering_name);
}

std::optional<protocol::Code> parse_code(const std::string& text, std::string* why) {
  if (text.empty() || text == "-") return protocol::Code{};
  return tetrapulse::parse_code(text, why);
}

}  // namespace tetrapulse::host
