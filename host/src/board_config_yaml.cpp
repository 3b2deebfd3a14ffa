#include "tetrapulse/host/board_config_yaml.hpp"

#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "tetrapulse/host/config_text.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/yaml_fields.hpp"

namespace tetrapulse::host {

using yaml_fields::Fields;

std::string format_board_config_yaml(const protocol::Config& c, const std::string& header) {
  std::string out;
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) out += "# " + line + "\n";
  std::string codes;
  for (size_t i = 0; i < c.codes.size(); ++i) codes += fmt::format("{}\"{}\"", i ? ", " : "", code_text(c.codes[i]));
  out += fmt::format("node_id: {}\n", c.node_id);
  out += fmt::format("target_id: {}\n", c.target_id);
  out += fmt::format("codes: [{}]  # marker 0..3; \"\" = no code (constant)\n", codes);
  out += fmt::format("modulation: {}  # on_off | two_level | constant\n", modulation_name(c.modulation));
  out += fmt::format("low_level: {}  # 0-bit emission, x/65535 (two_level)\n", c.low_level);
  out += fmt::format("bit_period_ns: {}\n", c.bit_period_ns);
  out += fmt::format("epoch_ns: {}\n", c.epoch_ns);
  out += fmt::format("brightness: {}  # 1-bit emission, x/65535\n", c.brightness);
  out += fmt::format("current_limit_ma: {}  # 0 = the board's hardware maximum\n", c.current_limit_ma);
  out += fmt::format("sync_source: {}  # none | gpio | can\n", sync_source_name(c.sync_source));
  out += fmt::format("gpio_edge: {}  # rising | falling\n", gpio_edge_name(c.gpio_edge));
  out += fmt::format("gpio_edge_period_ns: {}\n", c.gpio_edge_period_ns);
  out += fmt::format("gpio_edge_epoch_ns: {}\n", c.gpio_edge_epoch_ns);
  out += fmt::format("gpio_edge_numbering: {}  # nearest_coarse_time | count_after_gap\n",
                     gpio_edge_numbering_name(c.gpio_edge_numbering));
  return out;
}

namespace {

const std::set<std::string> kFields = {"node_id",     "target_id",        "codes",         "modulation",
                                       "low_level",   "bit_period_ns",    "epoch_ns",      "brightness",
                                       "current_limit_ma", "sync_source", "gpio_edge",     "gpio_edge_period_ns",
                                       "gpio_edge_epoch_ns", "gpio_edge_numbering"};

class ConfigReader {
 public:
  ConfigReader(const YAML::Node& doc, const std::string& name) : doc_(doc), f_(name) {}

  template <class T>
  void integer(const char* key, T* out, int64_t min = std::numeric_limits<T>::min(),
               int64_t max = std::numeric_limits<T>::max()) {
    const YAML::Node n = f_.child(doc_, key, "", false);
    if (!n.IsDefined()) return;
    const auto v = f_.scalar<int64_t>(n, key, "an integer");
    if (f_.failed()) return;
    if (v < min || v > max) {
      f_.fail(n, fmt::format("{}: {} is outside {}..{}", key, v, min, max));
      return;
    }
    *out = static_cast<T>(v);
  }

  template <class E, class Parse>
  void name(const char* key, E* out, Parse parse, const char* choices) {
    const YAML::Node n = f_.child(doc_, key, "", false);
    if (!n.IsDefined()) return;
    const auto text = f_.scalar<std::string>(n, key, choices);
    if (f_.failed()) return;
    const std::optional<E> v = parse(text);
    if (!v) {
      f_.fail(n, fmt::format("{}: '{}' is not one of {}", key, text, choices));
      return;
    }
    *out = *v;
  }

  void codes(protocol::Config* c) {
    const YAML::Node n = f_.child(doc_, "codes", "", false);
    if (!n.IsDefined()) return;
    if (!n.IsSequence() || n.size() != c->codes.size()) {
      f_.fail(n, fmt::format("codes: expected a list of {} code strings (marker 0..3)", c->codes.size()));
      return;
    }
    for (size_t i = 0; i < c->codes.size(); ++i) {
      const std::string field = fmt::format("codes[{}]", i);
      const auto text = f_.scalar<std::string>(n[i], field, "a string of 0 and 1");
      if (f_.failed()) return;
      std::string why;
      const std::optional<protocol::Code> code = parse_code(text, &why);
      if (!code) {
        f_.fail(n[i], fmt::format("{}: '{}' {}", field, text, why));
        return;
      }
      c->codes[i] = *code;
    }
  }

  void unknown_fields() {
    for (const auto& kv : doc_) {
      const std::string key = kv.first.Scalar();
      if (kFields.count(key) == 0) f_.fail(kv.first, fmt::format("{}: not a board configuration field", key));
    }
  }

  Fields& fields() { return f_; }

 private:
  YAML::Node doc_;
  Fields f_;
};

}  // namespace

HostResult<protocol::Config> parse_board_config_yaml(const std::string& text, const std::string& name) {
  auto doc = yaml_fields::load_yaml(text, name);
  if (!doc) return host_error(HostErrorKind::kBadFile, "", doc.error().what());
  protocol::Config c = protocol::default_config();
  ConfigReader r(*doc, name);
  r.unknown_fields();
  r.integer("node_id", &c.node_id, 1, 254);
  r.integer("target_id", &c.target_id);
  r.codes(&c);
  r.name("modulation", &c.modulation, parse_modulation, "on_off, two_level, constant");
  r.integer("low_level", &c.low_level);
  r.integer("bit_period_ns", &c.bit_period_ns, protocol::kMinBitPeriodNs);
  r.integer("epoch_ns", &c.epoch_ns);
  r.integer("brightness", &c.brightness);
  r.integer("current_limit_ma", &c.current_limit_ma);
  r.name("sync_source", &c.sync_source, parse_sync_source, "none, gpio, can");
  r.name("gpio_edge", &c.gpio_edge, parse_gpio_edge, "rising, falling");
  r.integer("gpio_edge_period_ns", &c.gpio_edge_period_ns, protocol::kMinGpioEdgePeriodNs);
  r.integer("gpio_edge_epoch_ns", &c.gpio_edge_epoch_ns);
  r.name("gpio_edge_numbering", &c.gpio_edge_numbering, parse_gpio_edge_numbering,
         "nearest_coarse_time, count_after_gap");
  if (r.fields().failed()) return host_error(HostErrorKind::kBadFile, "", r.fields().error().what());
  if (const protocol::Status valid = protocol::validate(c); !valid) {
    return host_error(HostErrorKind::kBadFile, name,
                      fmt::format("not a valid configuration: {}", protocol::error_name(valid.error())), valid.error());
  }
  return c;
}

HostResult<protocol::Config> read_board_config_yaml(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return host_error(HostErrorKind::kBadFile, path, "is a folder, not a file");
  auto text = read_text_file(path);
  if (!text) return host_error(HostErrorKind::kBadFile, "", text.error().what());
  return parse_board_config_yaml(*text, path);
}

}  // namespace tetrapulse::host
