// `tetrapulse config`: show a board's running configuration, or set it from a board
// configuration file (`--file`, as `tetrapulse codebook` writes them) and/or from options,
// read it back to check, and optionally store it (`--persist`).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"
#include "tetrapulse/host/board_config_yaml.hpp"
#include "tetrapulse/host/config_text.hpp"

namespace tetrapulse::cli {
namespace {

using host::HostErrorKind;

struct ConfigArgs {
  BoardOptions board;
  std::string file;
  bool persist = false;
  bool factory_reset = false;
  std::optional<int64_t> node_id, target_id, low_level, bit_period_ns, epoch_ns, brightness, current_limit_ma,
      gpio_edge_period_ns, gpio_edge_epoch_ns;
  std::vector<std::string> codes;  // "I=BITS"
  std::optional<std::string> modulation, sync_source, gpio_edge, gpio_edge_numbering;

  bool sets_fields() const {
    return node_id || target_id || low_level || bit_period_ns || epoch_ns || brightness || current_limit_ma ||
           gpio_edge_period_ns || gpio_edge_epoch_ns || !codes.empty() || modulation || sync_source || gpio_edge ||
           gpio_edge_numbering;
  }
};

std::vector<uint8_t> bytes_of(const protocol::Config& c) {
  std::vector<uint8_t> out(protocol::kConfigSize);
  protocol::ByteWriter w(out.data(), out.size());
  protocol::encode_config(c, w);
  return out;
}

// The options on top of `c`; an error names the option.
host::HostResult<protocol::Config> apply_options(const ConfigArgs& a, protocol::Config c) {
  auto bad = [](const std::string& what) { return host::host_error(HostErrorKind::kBadInput, "", what); };
  if (a.node_id) c.node_id = static_cast<uint8_t>(*a.node_id);
  if (a.target_id) c.target_id = static_cast<uint16_t>(*a.target_id);
  if (a.low_level) c.low_level = static_cast<uint16_t>(*a.low_level);
  if (a.bit_period_ns) c.bit_period_ns = static_cast<uint32_t>(*a.bit_period_ns);
  if (a.epoch_ns) c.epoch_ns = *a.epoch_ns;
  if (a.brightness) c.brightness = static_cast<uint16_t>(*a.brightness);
  if (a.current_limit_ma) c.current_limit_ma = static_cast<uint16_t>(*a.current_limit_ma);
  if (a.gpio_edge_period_ns) c.gpio_edge_period_ns = static_cast<uint32_t>(*a.gpio_edge_period_ns);
  if (a.gpio_edge_epoch_ns) c.gpio_edge_epoch_ns = *a.gpio_edge_epoch_ns;
  for (const std::string& spec : a.codes) {
    const size_t eq = spec.find('=');
    const std::string index = spec.substr(0, eq);
    if (eq == std::string::npos || index.size() != 1 || index[0] < '0' || index[0] > '3') {
      return bad(fmt::format("--code {}: expected MARKER=BITS with MARKER 0..3, e.g. 0=1101001110", spec));
    }
    std::string why;
    const auto code = host::parse_code(spec.substr(eq + 1), &why);
    if (!code) return bad(fmt::format("--code {}: '{}' {}", spec, spec.substr(eq + 1), why));
    c.codes[static_cast<size_t>(index[0] - '0')] = *code;
  }
  if (a.modulation) c.modulation = *host::parse_modulation(*a.modulation);
  if (a.sync_source) c.sync_source = *host::parse_sync_source(*a.sync_source);
  if (a.gpio_edge) c.gpio_edge = *host::parse_gpio_edge(*a.gpio_edge);
  if (a.gpio_edge_numbering) c.gpio_edge_numbering = *host::parse_gpio_edge_numbering(*a.gpio_edge_numbering);
  return c;
}

int show(host::Board& board, bool json) {
  auto config = board.config();
  if (!config) return report_failure("config", config.error());
  if (json) {
    fmt::print("{}\n", config_json(board.name(), *config));
  } else {
    fmt::print("{}", host::format_board_config_yaml(*config, "running configuration of " + board.name()));
  }
  return kExitOk;
}

int run_config(const ConfigArgs& a) {
  // Inputs first: a bad file or option fails before any board is touched.
  std::optional<protocol::Config> from_file;
  if (!a.file.empty()) {
    auto c = host::read_board_config_yaml(a.file);
    if (!c) return report_failure("config", c.error());
    from_file = *c;
  }
  auto board = open_board(a.board);
  if (!board) return report_failure("config", board.error());
  host::Board& b = **board;
  if (a.factory_reset) {
    if (auto done = b.factory_reset(); !done) return report_failure("config", done.error());
  }
  if (!from_file && !a.sets_fields()) {
    if (a.persist) {
      if (auto done = b.persist(); !done) return report_failure("config", done.error());
    }
    return a.factory_reset && !a.persist ? kExitOk : show(b, a.board.json);
  }
  protocol::Config base;
  if (from_file) {
    base = *from_file;
  } else {
    auto running = b.config();
    if (!running) return report_failure("config", running.error());
    base = *running;
  }
  auto wanted = apply_options(a, base);
  if (!wanted) return report_failure("config", wanted.error());
  if (auto done = b.configure(*wanted); !done) return report_failure("config", done.error());
  // Read back, except when a CAN board was just moved to another node id.
  const bool moved = b.name().rfind("can:", 0) == 0 && wanted->node_id != base.node_id;
  if (!moved) {
    auto back = b.config();
    if (!back) return report_failure("config", back.error());
    if (bytes_of(*back) != bytes_of(*wanted)) {
      std::fprintf(stderr, "tetrapulse config: %s: the configuration read back differs from the one sent\n",
                   b.name().c_str());
      return kExitCheckFailed;
    }
  }
  if (a.persist) {
    if (auto done = b.persist(); !done) return report_failure("config", done.error());
  }
  if (a.board.json) {
    fmt::print("{}\n", JsonObject()
                           .str("address", b.name())
                           .flag("configured", true)
                           .flag("verified", !moved)
                           .flag("persisted", a.persist)
                           .raw("config", config_json(b.name(), *wanted))
                           .text());
  } else {
    fmt::print("{}: configured{}{}\n", b.name(), moved ? fmt::format(" (now node {}: not read back)", wanted->node_id) : " and read back",
               a.persist ? ", persisted" : " (not persisted: --persist stores it)");
  }
  return kExitOk;
}

}  // namespace

void add_config_command(CLI::App& app, int* result) {
  auto a = std::make_shared<ConfigArgs>();
  auto* cmd = app.add_subcommand(
      "config", "Show a board's configuration, or set it from a board configuration file and/or options");
  add_board_options(cmd, &a->board);
  cmd->add_option("--file", a->file, "Board configuration YAML (as `tetrapulse codebook` writes) to apply")
      ->group("Configuration");
  cmd->add_flag("--persist", a->persist, "Store the configuration in the board's flash")->group("Configuration");
  cmd->add_flag("--factory-reset", a->factory_reset, "Go back to the factory configuration first")
      ->group("Configuration");
  const char* g = "Fields (SPEC.md 2.5; applied over --file, or over the running configuration)";
  cmd->add_option("--node-id", a->node_id, "CAN node id")->check(CLI::Range(1, 254))->group(g);
  cmd->add_option("--target-id", a->target_id, "Target (codebook) id")->check(CLI::Range(0, 65535))->group(g);
  cmd->add_option("--code", a->codes, "MARKER=BITS, e.g. 0=1101001110 (BITS '' or - for no code); repeatable")
      ->group(g);
  cmd->add_option("--modulation", a->modulation, "on_off, two_level or constant")
      ->check(CLI::IsMember({"on_off", "two_level", "constant"}))
      ->group(g);
  cmd->add_option("--low-level", a->low_level, "0-bit emission with two_level, x/65535")
      ->check(CLI::Range(0, 65535))
      ->group(g);
  cmd->add_option("--bit-period-ns", a->bit_period_ns, "Code bit period")
      ->check(CLI::Range(int64_t{protocol::kMinBitPeriodNs}, int64_t{UINT32_MAX}))
      ->group(g);
  cmd->add_option("--epoch-ns", a->epoch_ns, "Rig time at which bit 0 starts")->group(g);
  cmd->add_option("--brightness", a->brightness, "1-bit emission, x/65535")->check(CLI::Range(0, 65535))->group(g);
  cmd->add_option("--current-limit-ma", a->current_limit_ma, "LED current ceiling, 0 = hardware maximum")
      ->check(CLI::Range(0, 65535))
      ->group(g);
  cmd->add_option("--sync-source", a->sync_source, "none, gpio or can")
      ->check(CLI::IsMember({"none", "gpio", "can"}))
      ->group(g);
  cmd->add_option("--gpio-edge", a->gpio_edge, "Sync input edge: rising or falling")
      ->check(CLI::IsMember({"rising", "falling"}))
      ->group(g);
  cmd->add_option("--gpio-edge-period-ns", a->gpio_edge_period_ns, "Nominal interval between sync edges")
      ->check(CLI::Range(int64_t{protocol::kMinGpioEdgePeriodNs}, int64_t{UINT32_MAX}))
      ->group(g);
  cmd->add_option("--gpio-edge-epoch-ns", a->gpio_edge_epoch_ns, "Rig time of sync edge 0")->group(g);
  cmd->add_option("--gpio-edge-numbering", a->gpio_edge_numbering, "nearest_coarse_time or count_after_gap")
      ->check(CLI::IsMember({"nearest_coarse_time", "count_after_gap"}))
      ->group(g);
  cmd->callback([a, result] { *result = run_config(*a); });
}

}  // namespace tetrapulse::cli
